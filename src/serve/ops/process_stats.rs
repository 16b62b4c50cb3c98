//! The process's own figures for `/metrics`, read from `/proc/self` at each scrape (Linux; none
//! elsewhere): memory, CPU time, open file descriptors against their limit, threads, start
//! time — what an operator compares with the unit's `MemoryMax`, `LimitNOFILE` and `TasksMax`.
//! The series carry Prometheus' usual `process_*` names.

/// One reading of the process's figures; `None` where `/proc` did not say.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ProcessStats {
    /// Resident memory, in bytes (`VmRSS`).
    pub resident_bytes: Option<f64>,
    /// Virtual memory, in bytes (`VmSize`).
    pub virtual_bytes: Option<f64>,
    /// User and system CPU time, in seconds.
    pub cpu_seconds: Option<f64>,
    /// Open file descriptors.
    pub open_fds: Option<f64>,
    /// The soft limit on open file descriptors.
    pub max_fds: Option<f64>,
    /// Threads.
    pub threads: Option<f64>,
    /// When the process started, in Unix seconds.
    pub start_time: Option<f64>,
}

/// Clock ticks per second of `/proc/*/stat`'s times: USER_HZ, 100 on every Linux architecture
/// (the kernel scales to it whatever its own tick rate).
const USER_HZ: f64 = 100.0;

impl ProcessStats {
    /// Reads `/proc/self` now.
    #[must_use]
    pub fn read() -> Self {
        let mut s = Self::default();
        if let Ok(status) = std::fs::read_to_string("/proc/self/status") {
            s.resident_bytes = status_kib(&status, "VmRSS:").map(|k| k * 1024.0);
            s.virtual_bytes = status_kib(&status, "VmSize:").map(|k| k * 1024.0);
            s.threads = status_kib(&status, "Threads:");
        }
        let stat = std::fs::read_to_string("/proc/self/stat").ok();
        if let Some(fields) = stat.as_deref().and_then(stat_fields) {
            let num = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok());
            // Fields 14 and 15 (utime, stime) and 22 (starttime) of proc(5), counted from 1;
            // `fields` starts at field 3.
            if let (Some(u), Some(sys)) = (num(11), num(12)) {
                s.cpu_seconds = Some((u + sys) / USER_HZ);
            }
            let boot = std::fs::read_to_string("/proc/stat")
                .ok()
                .and_then(|t| status_kib(&t, "btime"));
            if let (Some(start), Some(boot)) = (num(19), boot) {
                s.start_time = Some(boot + start / USER_HZ);
            }
        }
        if let Ok(dir) = std::fs::read_dir("/proc/self/fd") {
            s.open_fds = Some(dir.count() as f64);
        }
        if let Ok(limits) = std::fs::read_to_string("/proc/self/limits") {
            s.max_fds = limits
                .lines()
                .find(|l| l.starts_with("Max open files"))
                .and_then(|l| l["Max open files".len()..].split_whitespace().next())
                .and_then(|v| v.parse().ok());
        }
        s
    }
}

/// The number after `key` on its line of a `/proc` key-value file (`VmRSS:   1234 kB`).
fn status_kib(text: &str, key: &str) -> Option<f64> {
    text.lines()
        .find_map(|l| l.strip_prefix(key))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|v| v.parse().ok())
}

/// `/proc/self/stat`'s fields from the third (state) on: after the command name, which is in
/// parentheses and may itself hold spaces or parentheses.
fn stat_fields(stat: &str) -> Option<Vec<&str>> {
    let (_, rest) = stat.rsplit_once(") ")?;
    Some(rest.split_whitespace().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stat_fields_start_after_the_command_name_whatever_it_holds() {
        let line = "42 (a) b (c) S 1 42 42 0 -1 4194560 1 0 0 0 250 50 0 0 20 0 3 0 777 1000 10";
        let f = stat_fields(line).unwrap();
        assert_eq!(f[0], "S");
        assert_eq!((f[11], f[12]), ("250", "50"));
        assert_eq!(f[17], "3", "num_threads, field 20");
        assert_eq!(f[19], "777", "starttime, field 22");
        assert_eq!(
            status_kib("Name:\tx\nVmRSS:\t  2048 kB\n", "VmRSS:"),
            Some(2048.0)
        );
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn this_process_has_memory_cpu_time_and_open_files() {
        let s = ProcessStats::read();
        assert!(s.resident_bytes.is_some_and(|b| b > 1e5), "{s:?}");
        assert!(s.cpu_seconds.is_some_and(|c| c >= 0.0), "{s:?}");
        assert!(s.open_fds.is_some_and(|n| n >= 3.0), "{s:?}");
        assert!(s.max_fds.is_some_and(|n| n >= s.open_fds.unwrap()), "{s:?}");
        assert!(s.threads.is_some_and(|n| n >= 1.0), "{s:?}");
        assert!(s.start_time.is_some_and(|t| t > 1.5e9), "{s:?}");
    }
}
