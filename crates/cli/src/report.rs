//! The text report printed at the end of a run, and number formatting for humans.

use flexdem_run::{Status, Summary};
use std::fmt::Write;

/// A duration in seconds for humans: `850 ms`, `12.3 s`, `4 min 05 s`, `2 h 03 min`.
pub fn human_duration(seconds: f64) -> String {
    if !seconds.is_finite() || seconds < 0.0 {
        return "?".into();
    }
    if seconds < 1.0 {
        format!("{:.0} ms", seconds * 1e3)
    } else if seconds < 60.0 {
        format!("{seconds:.1} s")
    } else if seconds < 3600.0 {
        let s = seconds.round() as u64;
        format!("{} min {:02} s", s / 60, s % 60)
    } else {
        let m = (seconds / 60.0).round() as u64;
        format!("{} h {:02} min", m / 60, m % 60)
    }
}

/// `count noun` with the noun in the plural unless the count is 1 (`1 sphere`, `2 spheres`).
pub fn plural(count: usize, noun: &str) -> String {
    if count == 1 {
        format!("{count} {noun}")
    } else {
        format!("{count} {noun}s")
    }
}

/// The end-of-run report: steps, times, stages, energy and balance, counts, and where the
/// output is and how to open it.
pub fn text(summary: &Summary) -> String {
    let mut s = String::new();
    let status = match summary.status {
        Status::Completed => "run completed",
        Status::Interrupted => "run interrupted",
        Status::Failed => "run failed",
    };
    let _ = writeln!(
        s,
        "{status}: {} steps ({} in this run), simulated time {:.6e} s, dt {:.3e} s (critical {:.3e} s)",
        summary.steps, summary.steps_this_run, summary.time, summary.dt, summary.critical_dt
    );
    let _ = writeln!(
        s,
        "wall time {} on {} thread{}, {:.0} steps/s",
        human_duration(summary.wall_time),
        summary.threads,
        if summary.threads == 1 { "" } else { "s" },
        summary.steps_per_second
    );
    let st = &summary.stages;
    let wall = summary.wall_time.max(f64::MIN_POSITIVE);
    let pct = |x: f64| 100.0 * x / wall;
    let _ = writeln!(
        s,
        "stages: collision {:.1} %, contacts {:.1} %, links {:.1} %, loads {:.1} %, integration {:.1} %, bookkeeping {:.1} %, other (output, checkpoints) {:.1} %",
        pct(st.collision),
        pct(st.contacts),
        pct(st.links),
        pct(st.loads),
        pct(st.integration),
        pct(st.bookkeeping),
        pct(st.other)
    );
    let c = &summary.counts;
    let _ = writeln!(
        s,
        "bodies: {} ({}, {}), {} ({} broken), {}, {}; {}",
        plural(c.particles, "particle"),
        plural(c.spheres, "sphere"),
        plural(c.nodes, "node"),
        plural(c.connections, "connection"),
        c.broken_links,
        plural(c.pfacets, "PFacet"),
        plural(c.walls, "wall"),
        plural(c.contacts, "contact")
    );
    let e = &summary.energy;
    // `+ 0.0` turns −0 into 0 for printing
    let mut t = e.terms;
    for x in [
        &mut t.kinetic_translation,
        &mut t.kinetic_rotation,
        &mut t.elastic_links,
        &mut t.elastic_contacts,
        &mut t.gravity_work,
        &mut t.load_work,
        &mut t.boundary_work,
        &mut t.contact_births,
        &mut t.damping,
        &mut t.links_dissipated,
        &mut t.friction,
        &mut t.contact_damping,
        &mut t.contact_releases,
    ] {
        *x += 0.0;
    }
    let _ = writeln!(
        s,
        "energy (J): kinetic {:.4e} + {:.4e} (rotation), elastic links {:.4e}, contacts {:.4e}; \
         work of gravity {:.4e}, of loads {:.4e}, of boundaries {:.4e}; contact births and ends {:.4e}; \
         dissipated by damping {:.4e}, links {:.4e}, friction {:.4e}, contact dashpots {:.4e}; \
         released by contacts {:.4e}",
        t.kinetic_translation,
        t.kinetic_rotation,
        t.elastic_links,
        t.elastic_contacts,
        t.gravity_work,
        t.load_work,
        t.boundary_work,
        t.contact_births,
        t.damping,
        t.links_dissipated,
        t.friction,
        t.contact_damping,
        t.contact_releases
    );
    let _ = writeln!(
        s,
        "energy balance: {:.6e} J (initial {:.6e} J), error {:.2e} of the energy scale {:.3e} J{}",
        e.balance,
        e.initial_balance,
        e.relative_balance_error + 0.0,
        e.scale,
        match e.contacts_born_deep {
            0 => String::new(),
            n if e.late_contacts_energy > 0.0 => format!(
                "; {} found late, those after the first step putting in {:.3e} J",
                plural(n as usize, "contact"),
                e.late_contacts_energy
            ),
            n => format!("; {} found late", plural(n as usize, "contact")),
        }
    );
    match &summary.output {
        Some(o) => {
            let _ = writeln!(s, "output in {}:", o.directory.display());
            if let Some(pvd) = &o.pvd {
                let _ = writeln!(
                    s,
                    "  {} VTK frames: open them in ParaView with `paraview {}`",
                    o.vtk_frames,
                    pvd.display()
                );
            }
            if let Some(csv) = &o.csv {
                let _ = writeln!(s, "  {} rows of series: {}", o.series_rows, csv.display());
            }
            if let Some(png) = &o.plot {
                let _ = writeln!(s, "  plot of the series: {}", png.display());
            }
        }
        None => {
            let _ = writeln!(s, "no output written");
        }
    }
    if let Some(cp) = &summary.checkpoint {
        let _ = writeln!(
            s,
            "checkpoint: {} (continue with `flexdem resume {}`)",
            cp.display(),
            cp.display()
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::human_duration;

    #[test]
    fn durations_read_naturally() {
        assert_eq!(human_duration(0.25), "250 ms");
        assert_eq!(human_duration(12.34), "12.3 s");
        assert_eq!(human_duration(245.0), "4 min 05 s");
        assert_eq!(human_duration(7380.0), "2 h 03 min");
        assert_eq!(human_duration(f64::NAN), "?");
    }

    #[test]
    fn plurals() {
        assert_eq!(super::plural(1, "sphere"), "1 sphere");
        assert_eq!(super::plural(0, "PFacet"), "0 PFacets");
    }
}
