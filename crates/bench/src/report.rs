//! The results as an aligned text table and as CSV.

use crate::runner::PlanRow;
use std::fmt::Write as _;

/// The table's columns: (title, width).
const COLUMNS: [(&str, usize); 17] = [
    ("scene", 11),
    ("size", 8),
    ("elements", 9),
    ("thr", 3),
    ("steps", 6),
    ("ms/step", 9),
    ("ns/elem-step", 12),
    ("steps/s", 9),
    ("cpu%", 4),
    ("coll%", 5),
    ("cont%", 5),
    ("link%", 5),
    ("intg%", 5),
    ("rest%", 5),
    ("contacts", 8),
    ("B/elem", 6),
    ("vs 1st thr", 10),
];

/// The table's header line and a rule under it.
pub fn table_header() -> String {
    let titles: Vec<String> = COLUMNS
        .iter()
        .enumerate()
        .map(|(i, (t, w))| if i == 0 { format!("{t:<w$}") } else { format!("{t:>w$}") })
        .collect();
    let line = titles.join(" ");
    let rule = "-".repeat(line.chars().count());
    format!("{line}\n{rule}")
}

/// One table line for `row`; stage shares are of the timed wall time, `rest%` is the time
/// outside the four stages (loads, checks, energy, time step estimates). The last column says
/// whether the final state is bit-identical to the first thread count's ("identical",
/// "DIFFERENT", "-" for the first).
pub fn table_row(row: &PlanRow) -> String {
    let r = &row.result;
    let pct = r.stage_percent();
    let cells = [
        r.case.name(),
        r.case.size().to_string(),
        r.elements().to_string(),
        r.threads.to_string(),
        r.steps.to_string(),
        format!("{:.3}", r.ms_per_step()),
        format!("{:.1}", r.ns_per_element_step()),
        format!("{:.1}", r.steps_per_second()),
        r.cpu_percent().map_or("?".into(), |c| format!("{c:.0}")),
        format!("{:.0}", pct[0]),
        format!("{:.0}", pct[1]),
        format!("{:.0}", pct[2]),
        format!("{:.0}", pct[3]),
        format!("{:.0}", pct[4]),
        r.contacts.to_string(),
        r.bytes_per_element().map_or("?".into(), |b| format!("{b:.0}")),
        verdict(row.same_as_first).to_string(),
    ];
    let mut out = String::new();
    for (i, (cell, (_, w))) in cells.iter().zip(COLUMNS).enumerate() {
        if i > 0 {
            out.push(' ');
        }
        if i == 0 {
            let _ = write!(out, "{cell:<w$}");
        } else {
            let _ = write!(out, "{cell:>w$}");
        }
    }
    out
}

fn verdict(same: Option<bool>) -> &'static str {
    match same {
        None => "-",
        Some(true) => "identical",
        Some(false) => "DIFFERENT",
    }
}

/// The CSV header (see [`csv_row`]).
pub const CSV_HEADER: &str = "scene,size,elements,particles,connections,pfacets,threads,\
warmup_steps,steps,dt_s,build_s,wall_s,cpu_s,ms_per_step,ns_per_element_step,steps_per_s,\
steps_per_cpu_s,\
collision_ms_per_step,contacts_ms_per_step,links_ms_per_step,integration_ms_per_step,\
collision_pct,contacts_pct,links_pct,integration_pct,other_pct,contacts,rss_delta_bytes,\
bytes_per_element,probe,probe_value,checksum,vs_first_threads,heap_delta_bytes,median_step_ms";

/// One CSV line for `row` (no newline): the columns of [`CSV_HEADER`]; an unknown memory
/// or a missing probe is an empty field, the checksum is hexadecimal.
pub fn csv_row(row: &PlanRow) -> String {
    let r = &row.result;
    let ms = r.stage_ms_per_step();
    let pct = r.stage_percent();
    let mut fields = vec![
        r.case.name(),
        r.case.size().to_string(),
        r.elements().to_string(),
        r.particles.to_string(),
        r.connections.to_string(),
        r.pfacets.to_string(),
        r.threads.to_string(),
        r.warmup_steps.to_string(),
        r.steps.to_string(),
        format!("{:e}", r.dt),
        format!("{:.6}", r.build_time.as_secs_f64()),
        format!("{:.6}", r.wall.as_secs_f64()),
        r.cpu.map_or(String::new(), |c| format!("{:.2}", c.as_secs_f64())),
        format!("{:.6}", r.ms_per_step()),
        format!("{:.3}", r.ns_per_element_step()),
        format!("{:.3}", r.steps_per_second()),
        r.steps_per_cpu_second().map_or(String::new(), |s| format!("{s:.3}")),
    ];
    fields.extend(ms.iter().map(|m| format!("{m:.6}")));
    fields.extend(pct.iter().map(|p| format!("{p:.2}")));
    fields.push(r.contacts.to_string());
    fields.push(r.memory_bytes.map_or(String::new(), |b| b.to_string()));
    fields.push(r.bytes_per_element().map_or(String::new(), |b| format!("{b:.1}")));
    fields.push(r.probe.map_or(String::new(), |(name, _)| name.to_string()));
    fields.push(r.probe.map_or(String::new(), |(_, v)| format!("{v:.9e}")));
    fields.push(format!("{:016x}", r.checksum));
    fields.push(verdict(row.same_as_first).to_string());
    fields.push(r.heap_bytes.map_or(String::new(), |b| b.to_string()));
    fields.push(format!("{:.6}", r.median_step_ms()));
    fields.join(",")
}

/// The whole CSV text of `rows`, header first, one line each.
pub fn csv(rows: &[PlanRow]) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for row in rows {
        out.push_str(&csv_row(row));
        out.push('\n');
    }
    out
}

/// The header of the steps' CSV ([`step_times_csv`]).
pub const STEP_TIMES_HEADER: &str = "scene,size,threads,step,ms";

/// Every timed step of `rows` (`BenchResult::step_walls`), one line each: the row's scene,
/// size and threads, the step's number in its run (from 0) and its wall time (ms).
pub fn step_times_csv(rows: &[PlanRow]) -> String {
    let mut out = String::from(STEP_TIMES_HEADER);
    out.push('\n');
    for row in rows {
        let r = &row.result;
        let (name, size) = (r.case.name(), r.case.size());
        for (k, wall) in r.step_walls.iter().enumerate() {
            let ms = wall.as_secs_f64() * 1e3;
            out.push_str(&format!("{name},{size},{},{k},{ms:.6}\n", r.threads));
        }
    }
    out
}
