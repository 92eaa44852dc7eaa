#!/usr/bin/env python3
"""flexdem against YADE 2023.02a on the twins of YADE's reference runs (bench/run_vs_yade.sh
calls this; see its header and bench/README.md, "YADE twins").

   python3 bench/yade/run.py --flexdem PATH [--yade yade] [--repeats 3] [SCENE ...]
   SCENE: tube, net, membrane20, membrane40, membrane80, membrane (the three), all (default)

For each scene the runs are interleaved, one process at a time: flexdem, YADE (each YADE
variant), flexdem, YADE, ... REPEATS times; each run builds the scene, runs WARMUP untimed
steps, then STEPS timed steps, 1 thread, output off. flexdem: `flexdem bench --scene-file`
(its wall time and process CPU time of the timed steps; a scene whose timed steps take less
than 1 s is run k times in the process and the mean taken, because flexdem's CPU clock ticks
in 10 ms); YADE: bench/yade/<scene>.py (wall
time and process CPU time of O.run(STEPS, True)). The medians are compared. Then one untimed
`flexdem run --no-output --steps WARMUP+STEPS --summary` gives flexdem's physical check values
(the same deterministic run as the timed one), and YADE's come from its timed runs.
Raw rows: bench/results/vs_yade_<scene>.csv.
"""
import argparse
import csv
import filecmp
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import twin  # noqa: E402

RESULTS = os.path.join(ROOT, 'bench', 'results')
SCENES_DIR = os.path.join(ROOT, 'bench', 'scenes')
GEN_DIR = os.path.join(ROOT, 'target', 'flexdem', 'bench', 'yade')
MIN_FLEXDEM_S = 1.0  # timed seconds per flexdem measurement (see run_flexdem)


def env_int(name, default):
    return int(os.environ.get(name, default))


def scene_table():
    """name -> (flexdem scene file, warm-up, steps, [(YADE variant, script args)], checks).
    checks: [(label, path in flexdem's summary, YADE key)]."""
    t = {
        'tube': dict(
            toml=os.path.join(SCENES_DIR, 'tube_impact_solid_yade.toml'),
            make=lambda d: twin.write_tube(d), dt=lambda: twin.tube_params()[-1],
            warmup=env_int('TUBE_WARMUP', 25), steps=env_int('TUBE_STEPS', 5800),
            yade=[('', ['tube_impact.py'])],
            checks=[('impactor vz (m/s)', ('tracked', 'impactor_velocity', 'impactor_velocity_vz_m_per_s'), 'YADE_IMPACTOR_VZ')],
            what='tube impact, scenario 2 "solid" (640 PFacets, 0.1121 kg sphere at 2 m/s)'),
        'net': dict(
            toml=os.path.join(SCENES_DIR, 'net_drop_yade.toml'),
            make=lambda d: twin.write_net(d), dt=lambda: twin.net_params()[-1],
            warmup=env_int('NET_WARMUP', 6000), steps=env_int('NET_STEPS', 20000),
            yade=[('', ['net_drop.py'])],
            checks=[('sphere z (m)', ('tracked', 'rock_position', 'rock_position_z_m'), 'YADE_SPHERE_Z'),
                    ('sphere vz (m/s)', ('tracked', 'rock_velocity', 'rock_velocity_vz_m_per_s'), 'YADE_SPHERE_VZ')],
            what='net drop (11 x 11 nodes, 220 connections, 4.19 kg sphere)'),
    }
    for n in (20, 40, 80):
        t['membrane%d' % n] = dict(
            toml=os.path.join(GEN_DIR, 'membrane_N%d.toml' % n),
            make=(lambda n: lambda d: twin.write_membrane(d, n))(n), dt=(lambda n: lambda: twin.membrane_params(n)[-1])(n),
            # flexdem's twin of each YADE variant: self-contact on / off (self_contact = false)
            flexdem={'self': os.path.join(GEN_DIR, 'membrane_N%d.toml' % n),
                     'noself': os.path.join(GEN_DIR, 'membrane_N%d_noself.toml' % n)},
            make_variants=(lambda n: lambda d: twin.write_membrane(d, n, False))(n),
            warmup=env_int('MEMBRANE_WARMUP', 50), steps=env_int('MEMBRANE_STEPS', 200),
            yade=[('noself', ['membrane_scaling.py', str(n), 'noself']), ('self', ['membrane_scaling.py', str(n), 'self'])],
            checks=[('sphere (N/4, N/4) vz (m/s)', ('tracked', 'probe_sphere_velocity', 'probe_sphere_velocity_vz_m_per_s'), 'YADE_SPHERE_VZ'),
                    ('node (N/2, N/2) z (m)', ('tracked', 'centre_node_position', 'centre_node_position_z_m'), 'YADE_NODE_Z'),
                    ('kinetic energy (J)', ('energy', 'kinetic_translation'), 'YADE_KE')],
            what='membrane N = %d (%d nodes, %d PFacets, %d spheres)' % (n, n * n, 2 * (n - 1)**2, (n // 2)**2))
    return t


def loadavg():
    with open('/proc/loadavg') as f:
        return f.read().split()[0]


def run_flexdem(flexdem, toml, warmup, steps, k=1):
    """`flexdem bench --scene-file` with `--threads 1,1,...` (k runs of the scene in one process,
    each built, warmed up and timed anew): the mean wall and CPU time of the timed steps. k > 1
    for short runs, because flexdem's CPU time has the 10 ms resolution of /proc/self/stat."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, 'bench.csv')
        env = dict(os.environ, RAYON_NUM_THREADS='1')
        subprocess.run([flexdem, 'bench', '--scene-file', toml, '--threads', ','.join(['1'] * k), '--warmup', str(warmup),
                        '--steps', str(steps), '--csv', out], check=True, env=env,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with open(out) as f:
            rows = list(csv.DictReader(f))
    assert len(rows) == k
    wall = sum(float(r['wall_s']) for r in rows) / k
    cpu = sum(steps / float(r['steps_per_cpu_s']) for r in rows) / k  # the CSV's cpu_s has 2 decimals
    return dict(dt=float(rows[0]['dt_s']), wall_s=wall, cpu_s=cpu, contacts=int(rows[-1]['contacts']), k=k)


def run_yade(yade, args, warmup, steps):
    env = dict(os.environ, WARMUP=str(warmup), STEPS=str(steps), OMP_NUM_THREADS='1')
    p = subprocess.run([yade, '-j', '1', '-n', '-x', os.path.join(HERE, args[0])] + args[1:], env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    vals = {}
    for line in p.stdout.splitlines():
        w = line.split()
        if len(w) == 2 and w[0].startswith('YADE_'):
            vals[w[0]] = float(w[1])
    if p.returncode != 0 or 'YADE_WALL_S' not in vals:
        sys.exit('YADE failed (%s):\n%s' % (' '.join(args), p.stdout[-3000:]))
    return dict(dt=vals['YADE_DT'], wall_s=vals['YADE_WALL_S'], cpu_s=vals['YADE_CPU_S'],
                contacts=int(vals['YADE_CONTACTS']), values=vals)


def flexdem_check(flexdem, toml, total_steps):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, 'summary.json')
        subprocess.run([flexdem, 'run', '--no-output', '--threads', '1', '--steps', str(total_steps), '--summary', out,
                        '-q', toml], check=True, env=dict(os.environ, RAYON_NUM_THREADS='1'))
        with open(out) as f:
            return json.load(f)


def dig(d, path):
    for k in path:
        d = d[k]
    return d


def fmt_ms(s, steps):
    return 1e3 * s / steps


def run_scene(name, sc, a):
    os.makedirs(GEN_DIR, exist_ok=True)
    toml = sc['toml']
    if toml.startswith(SCENES_DIR):  # committed: check that the generator still writes it
        with tempfile.TemporaryDirectory() as d:
            fresh = sc['make'](d)
            if not filecmp.cmp(fresh, toml, shallow=False):
                sys.exit('%s differs from what bench/yade/twin.py writes: regenerate it' % toml)
    else:
        sc['make'](GEN_DIR)
        if 'make_variants' in sc:
            sc['make_variants'](GEN_DIR)
    # flexdem's scene per variant: the twin of each YADE variant where flexdem has one
    fvariants = sc.get('flexdem', {'': toml})

    def fkey(variant):
        return variant if variant in fvariants else next(iter(fvariants))
    W, N = sc['warmup'], sc['steps']
    dt = sc['dt']()
    print('\n== %s: %s' % (name, sc['what']))
    print('   dt %r s (0.5 * YADE PWaveTimeStep), %d untimed + %d timed steps, 1 thread, output off, %d repeats interleaved'
          % (dt, W, N, a.repeats), flush=True)
    rows = []
    # runs of the timed steps per flexdem process: at least MIN_FLEXDEM_S of timed steps
    trial = run_flexdem(a.flexdem, toml, W, N)
    k = max(1, min(50, math.ceil(MIN_FLEXDEM_S / trial['wall_s'])))
    for r in range(1, a.repeats + 1):
        msg = []
        for fv, ftoml in fvariants.items():
            la = loadavg()
            f = run_flexdem(a.flexdem, ftoml, W, N, k)
            rows.append(dict(scene=name, code='flexdem', variant=fv, repeat=r, load=la, **f))
            msg.append('flexdem%s %.3f ms/step (CPU %.3f; mean of %d runs)'
                       % (' ' + fv if fv else '', fmt_ms(f['wall_s'], N), fmt_ms(f['cpu_s'], N), k))
        msg[0] = 'repeat %d: %s' % (r, msg[0])
        for variant, args in sc['yade']:
            la = loadavg()
            y = run_yade(a.yade, args, W, N)
            rows.append(dict(scene=name, code='yade', variant=variant, repeat=r, load=la, **y))
            msg.append('YADE%s %.3f ms/step (CPU %.3f)' % (' ' + variant if variant else '', fmt_ms(y['wall_s'], N), fmt_ms(y['cpu_s'], N)))
        print('   ' + ', '.join(msg), flush=True)
    summ = flexdem_check(a.flexdem, toml, W + N)
    # the time step must be the same fixed one in both codes
    for row in rows:
        if row['dt'] != dt:
            sys.exit('time steps differ: %s %s dt %r, twin.py %r' % (row['code'], row['variant'], row['dt'], dt))
    if summ['dt'] != dt or summ['steps'] != W + N:
        sys.exit('flexdem check run: dt %r steps %d, expected %r %d' % (summ['dt'], summ['steps'], dt, W + N))

    def med(code, variant, key):
        return statistics.median(row[key] for row in rows if row['code'] == code and row['variant'] == variant)

    print('   %-16s %10s %10s %12s %13s %9s' % ('', 'ms/step', 'CPU ms/st', 'steps/CPU-s', 'contacts end', 'ratio*'))
    for fv in fvariants:
        fw, fc = med('flexdem', fv, 'wall_s'), med('flexdem', fv, 'cpu_s')
        fcont = [row for row in rows if row['code'] == 'flexdem' and row['variant'] == fv][-1]['contacts']
        label = 'flexdem' + (' ' + fv if fv else '')
        print('   %-16s %10.3f %10.3f %12.1f %13d %9s' % (label, fmt_ms(fw, N), fmt_ms(fc, N), N / fc, fcont, ''))
    summary = []
    for variant, _ in sc['yade']:
        fw, fc = med('flexdem', fkey(variant), 'wall_s'), med('flexdem', fkey(variant), 'cpu_s')
        yw, yc = med('yade', variant, 'wall_s'), med('yade', variant, 'cpu_s')
        last = [row for row in rows if row['code'] == 'yade' and row['variant'] == variant][-1]
        label = 'YADE' + (' ' + variant if variant else '')
        print('   %-16s %10.3f %10.3f %12.1f %13d %5.1fx/%.1fx' % (label, fmt_ms(yw, N), fmt_ms(yc, N), N / yc, last['contacts'], yw / fw, yc / fc))
        summary.append((name, variant, fw, fc, yw, yc, last['values']))
    print('   (* ratio = YADE time / flexdem time per step (flexdem\'s twin of the same variant): wall / CPU; medians of %d)' % a.repeats)
    print('   physical check after %d steps:' % (W + N))
    for label, path, key in sc['checks']:
        ours = dig(summ, path)
        theirs = ', '.join('YADE%s %+.6g' % (' ' + v if v else '', s[6][key]) for s, (v, _) in zip(summary, sc['yade']))
        print('     %-28s flexdem %+.6g   %s' % (label, ours, theirs))
    os.makedirs(RESULTS, exist_ok=True)
    path = os.path.join(RESULTS, 'vs_yade_%s.csv' % name)
    keys = ['scene', 'code', 'variant', 'repeat', 'runs', 'load', 'warmup', 'steps', 'dt', 'wall_s', 'cpu_s', 'ms_per_step', 'cpu_ms_per_step',
            'steps_per_cpu_s', 'contacts'] + ['check:' + c[0] for c in sc['checks']]
    with open(path, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(keys)
        for row in rows:
            checks = [row['values'][c[2]] if row['code'] == 'yade' else '' for c in sc['checks']]
            w.writerow([row['scene'], row['code'], row['variant'], row['repeat'], row.get('k', 1), row['load'], W, N, repr(row['dt']),
                        '%.6f' % row['wall_s'], '%.6f' % row['cpu_s'], '%.6f' % fmt_ms(row['wall_s'], N),
                        '%.6f' % fmt_ms(row['cpu_s'], N), '%.3f' % (N / row['cpu_s']), row['contacts']] + checks)
        w.writerow([name, 'flexdem', 'check', '', 1, loadavg(), W, N, repr(summ['dt']), '', '', '', '', '', summ['counts']['contacts']] +
                   [repr(dig(summ, c[1])) for c in sc['checks']])
    return [(s, N) for s in summary]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('scenes', nargs='*', default=['all'])
    ap.add_argument('--flexdem', required=True)
    ap.add_argument('--yade', default='yade')
    ap.add_argument('--repeats', type=int, default=3)
    a = ap.parse_args()
    table = scene_table()
    names = []
    for s in a.scenes:
        if s == 'all':
            names += ['tube', 'membrane20', 'membrane40', 'membrane80', 'net']
        elif s == 'membrane':
            names += ['membrane20', 'membrane40', 'membrane80']
        elif s in table:
            names.append(s)
        else:
            sys.exit('unknown scene %r: tube, net, membrane20, membrane40, membrane80, membrane, all' % s)
    with open('/proc/cpuinfo') as f:
        cpu = next((l.split(':', 1)[1].strip() for l in f if l.startswith('model name')), '?')
    print('flexdem %s vs YADE (%s), 1 thread each; %s, %d cores, load %s' % (a.flexdem, a.yade, cpu, os.cpu_count(), loadavg()))
    allsum = []
    for name in names:
        allsum += run_scene(name, table[name], a)
    print('\n%-12s %-7s %17s %17s %15s %12s' % ('scene', 'YADE', 'flexdem ms/step', 'YADE ms/step', 'YADE/flexdem', 'steps/CPU-s'))
    print('%-12s %-7s %17s %17s %15s %12s' % ('', 'variant', 'wall    CPU', 'wall    CPU', 'wall   CPU', 'flex / YADE'))
    for (name, variant, fw, fc, yw, yc, _), n in allsum:
        print('%-12s %-7s %8.3f %8.3f %8.3f %8.3f %6.1fx %6.1fx %6.0f / %.0f' % (
            name, variant or '-', fmt_ms(fw, n), fmt_ms(fc, n), fmt_ms(yw, n), fmt_ms(yc, n), yw / fw, yc / fc, n / fc, n / yc))


if __name__ == '__main__':
    main()
