//! The link's figures as people read them: on the header (`link 480 kbit/s 1.1 ms`) and in the
//! session's last log line.

use std::time::Duration;

use super::pacing::LinkFigures;

/// The link part of the session's last log line: `; link 512 kbit/s, round trip 40 ms, …`.
pub fn link_summary(f: &LinkFigures) -> String {
    let Some(rate) = f.rate else {
        return String::new();
    };
    format!(
        "; link {}, round trip {}, most queued {} bytes, level steps {} down {} up",
        rate_text(rate),
        rtt_text(f.rtt),
        f.max_queued,
        f.steps_down,
        f.steps_up
    )
}

/// A round trip for people: `0.4 ms`, `35 ms`.
pub fn rtt_text(rtt: Duration) -> String {
    let ms = rtt.as_secs_f64() * 1000.0;
    if ms < 10.0 {
        format!("{ms:.1} ms")
    } else {
        format!("{ms:.0} ms")
    }
}

/// A link rate for people: `512 kbit/s`, `4.2 Mbit/s` (two significant figures at most).
pub fn rate_text(bytes_per_sec: f64) -> String {
    let kbit = bytes_per_sec * 8.0 / 1000.0;
    if kbit < 1000.0 {
        format!("{} kbit/s", round2(kbit))
    } else if kbit < 1_000_000.0 {
        format!("{} Mbit/s", round2(kbit / 1000.0))
    } else {
        format!("{} Gbit/s", round2(kbit / 1_000_000.0))
    }
}

/// `x` to two significant figures, without a trailing `.0`.
fn round2(x: f64) -> String {
    if x >= 100.0 {
        format!("{:.0}", (x / 10.0).round() * 10.0)
    } else if x >= 10.0 {
        format!("{:.0}", x.round())
    } else {
        let r = (x * 10.0).round() / 10.0;
        if r.fract() == 0.0 {
            format!("{r:.0}")
        } else {
            format!("{r:.1}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_and_round_trips_read_as_people_write_them() {
        assert_eq!(rate_text(64_000.0), "510 kbit/s");
        assert_eq!(rate_text(1_250_000.0), "10 Mbit/s");
        assert_eq!(rate_text(500.0), "4 kbit/s");
        assert_eq!(rate_text(530.0), "4.2 kbit/s");
        assert_eq!(rtt_text(Duration::from_micros(1_100)), "1.1 ms");
        assert_eq!(rtt_text(Duration::from_millis(35)), "35 ms");
        assert_eq!(link_summary(&LinkFigures::default()), "");
    }
}
