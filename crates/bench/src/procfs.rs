//! What this process uses, from `/proc/self` (Linux): resident memory and CPU time.

use std::time::Duration;

/// Resident set size (`VmRSS`) and its peak (`VmHWM`) in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rss {
    /// Current resident set size.
    pub current: u64,
    /// Peak resident set size since the process started.
    pub peak: u64,
}

/// This process's resident memory, or None where `/proc/self/status` cannot be read (not
/// Linux) or lacks the two lines.
pub fn resident_memory() -> Option<Rss> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_status(&status)
}

/// `VmRSS` and `VmHWM` of a `/proc/<pid>/status` text (lines such as `VmRSS:  1234 kB`).
pub fn parse_status(status: &str) -> Option<Rss> {
    let field = |name: &str| -> Option<u64> {
        let line = status.lines().find(|l| l.starts_with(name))?;
        let mut words = line[name.len()..].split_whitespace();
        let value: u64 = words.next()?.parse().ok()?;
        match words.next() {
            Some("kB") => Some(value * 1024),
            _ => None,
        }
    };
    Some(Rss { current: field("VmRSS:")?, peak: field("VmHWM:")? })
}

/// Clock ticks per second of `/proc/<pid>/stat` times (USER_HZ, 100 on Linux).
const TICKS_PER_SECOND: u64 = 100;

/// CPU time used so far by every thread of this process (user + system), with the 10 ms
/// resolution of `/proc/self/stat`; None where it cannot be read. On a shared machine,
/// `cpu / wall` below the thread count means the run did not get its cores.
pub fn cpu_time() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    parse_stat_cpu(&stat)
}

/// utime + stime (fields 14 and 15) of a `/proc/<pid>/stat` line. The command name
/// (field 2, in parentheses) may hold spaces, so fields are counted after its last `)`.
pub fn parse_stat_cpu(stat: &str) -> Option<Duration> {
    let rest = &stat[stat.rfind(')')? + 1..];
    let mut fields = rest.split_whitespace().skip(11); // field 3 is the first after ')'
    let utime: u64 = fields.next()?.parse().ok()?;
    let stime: u64 = fields.next()?.parse().ok()?;
    let ticks = utime + stime;
    Some(Duration::from_millis(ticks * 1000 / TICKS_PER_SECOND))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_two_memory_lines_in_bytes() {
        let text = "Name:\tflexdem\nVmHWM:\t  2048 kB\nVmRSS:\t  1024 kB\nThreads:\t1\n";
        assert_eq!(parse_status(text), Some(Rss { current: 1024 * 1024, peak: 2048 * 1024 }));
        assert_eq!(parse_status("VmRSS: 12 kB\n"), None);
        assert_eq!(parse_status("VmRSS: 12 MB\nVmHWM: 12 kB\n"), None);
    }

    #[test]
    fn reads_user_and_system_ticks() {
        // pid (comm with ") spaces") state ppid pgrp session tty tpgid flags minflt cminflt
        // majflt cmajflt utime stime ...
        let line = "42 (a ) b) R 1 2 3 4 5 6 7 8 9 10 250 30 0 0 20 0 3";
        assert_eq!(parse_stat_cpu(line), Some(Duration::from_millis(2800)));
        assert_eq!(parse_stat_cpu("42 (x) R 1 2"), None);
    }

    #[test]
    fn this_process_has_memory_and_cpu_time_on_linux() {
        if cfg!(target_os = "linux") {
            let rss = resident_memory().expect("/proc/self/status");
            assert!(rss.current > 0 && rss.peak >= rss.current);
            // Spinning for 30 ms of CPU time shows up, however loaded the machine.
            let before = cpu_time().expect("/proc/self/stat");
            let start = std::time::Instant::now();
            let mut x = 1u64;
            while cpu_time().unwrap() < before + Duration::from_millis(30) {
                for _ in 0..100_000 {
                    x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
                }
                assert!(start.elapsed() < Duration::from_secs(20), "no CPU time counted");
            }
            std::hint::black_box(x);
        }
    }
}
