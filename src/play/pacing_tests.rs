//! The pacer on a simulated link and on single frames: steps down, steps up, shrinking, asking.

use super::*;

const PERIOD: Duration = Duration::from_millis(33);

fn sample(outstanding: u64, rate: u64) -> LinkSample {
    LinkSample {
        outstanding,
        rtt: Duration::from_millis(20),
        min_rtt: Duration::from_micros(100),
        delivery_rate: rate,
        ..LinkSample::default()
    }
}

/// A session on a simulated link, looked at every 3 ms (how often a session looks at its
/// link while a frame waits): a frame of [`sizes`] wire bytes at its level is wanted every
/// period and sent once the pacer says so, stepping as it says.
struct Sim {
    p: LinkPacer,
    wire: u64,
    now: Instant,
    level: ColorLevel,
    /// The wire's share of a frame's bytes.
    ratio: f64,
    /// The share the transport could shrink frames to.
    could_shrink: Option<f64>,
}

impl Sim {
    fn new(level: ColorLevel) -> Self {
        Self {
            p: LinkPacer::new(PERIOD, level),
            wire: 0,
            now: Instant::now(),
            level,
            ratio: 1.0,
            could_shrink: None,
        }
    }

    /// `secs` on a link of `rate` bytes/s; the levels used, in order.
    fn run(&mut self, rate: f64, secs: f64) -> Vec<ColorLevel> {
        let step = Duration::from_millis(3);
        let end = self.now + Duration::from_secs_f64(secs);
        let mut outstanding = 0.0f64;
        let mut next_want = self.now;
        let mut levels = vec![self.level];
        while self.now < end {
            outstanding = (outstanding - rate * step.as_secs_f64()).max(0.0);
            let s = sample(outstanding as u64, rate as u64);
            if self.now >= next_want && self.p.clear(self.wire, Some(&s), true, self.now) {
                let shrink = self.could_shrink.filter(|r| *r < self.ratio);
                match self.p.step(self.level, self.now, shrink) {
                    Some(Step::Down(l) | Step::Up(l)) => {
                        self.level = l;
                        levels.push(l);
                    }
                    Some(Step::Shrink) => self.ratio = shrink.expect("offered"),
                    None => {}
                }
                self.p
                    .sent(self.wire, sizes(self.level), self.level, self.now);
                let wire = (sizes(self.level) as f64 * self.ratio) as u64;
                self.wire += wire;
                outstanding += wire as f64;
                next_want = self.now + PERIOD;
            }
            self.now += step;
        }
        levels
    }
}

fn sizes(level: ColorLevel) -> u64 {
    match level {
        ColorLevel::TrueColor => 33_000,
        ColorLevel::Ansi256 => 8_000,
        _ => 3_000,
    }
}

#[test]
fn the_next_frame_waits_until_the_last_is_written_and_nearly_acknowledged() {
    let t = Instant::now();
    let mut p = LinkPacer::new(PERIOD, ColorLevel::Ansi256);
    assert!(p.clear(0, None, true, t), "nothing in flight");
    p.sent(1000, 8000, ColorLevel::Ansi256, t);
    assert!(
        !p.clear(1000, Some(&sample(0, 1_000_000)), true, t),
        "not yet written"
    );
    assert!(
        !p.clear(9000, Some(&sample(8000, 1_000_000)), true, t),
        "written, unacknowledged"
    );
    assert_eq!(p.waiting(t + PERIOD), Some(PERIOD));
    assert!(p.clear(
        9000,
        Some(&sample(MIN_ALLOWANCE, 1_000_000)),
        true,
        t + PERIOD
    ));
    // It was wanted at `t` (the first look) and could go at `t + PERIOD`.
    assert_eq!(p.take_waited(), Some(PERIOD));
    assert_eq!(p.take_waited(), None);
    assert_eq!(p.waiting(t + PERIOD), None);
    // Without the kernel's figures, a written frame is enough.
    p.sent(9000, 1, ColorLevel::Ansi256, t);
    assert!(!p.clear(9000, None, true, t));
    assert!(p.clear(9001, None, true, t));
}

#[test]
fn a_path_that_holds_more_than_a_frame_may_keep_it_in_flight() {
    let t = Instant::now();
    let mut p = LinkPacer::new(PERIOD, ColorLevel::Ansi256);
    p.sent(0, 30_000, ColorLevel::Ansi256, t);
    // 2.5 MB/s over an 80 ms path holds 200 kB: a 20 kB frame still queued is no wait.
    let far = LinkSample {
        outstanding: 20_000,
        min_rtt: Duration::from_millis(80),
        delivery_rate: 2_500_000,
        ..LinkSample::default()
    };
    assert!(p.clear(30_000, Some(&far), true, t));
}

#[test]
fn a_slow_link_steps_truecolor_down_to_where_it_carries_fifteen_frames() {
    use ColorLevel::*;
    // 64 kB/s: truecolor (33 kB) ~2 fps, 256 (8 kB) 8 fps, 16 colours (3 kB) 21 fps.
    let mut sim = Sim::new(TrueColor);
    assert_eq!(
        sim.run(64_000.0, 10.0),
        [TrueColor, Ansi256, Ansi16],
        "down twice, never back up (16 colours would need 1.5 x the rate for 256)"
    );
    assert_eq!(sim.p.figures().steps_down, 2);
    assert_eq!(sim.p.figures().steps_up, 0);
}

#[test]
fn a_fast_link_keeps_its_level_and_a_link_that_recovers_steps_back_up() {
    use ColorLevel::*;
    assert_eq!(Sim::new(TrueColor).run(10_000_000.0, 5.0), [TrueColor]);
    let mut sim = Sim::new(TrueColor);
    assert_eq!(sim.run(200_000.0, 4.0), [TrueColor, Ansi256]);
    // The link widens to 2 MB/s: after the hold, back to truecolor, and it stays.
    assert_eq!(sim.run(2_000_000.0, 8.0), [Ansi256, TrueColor]);
    assert_eq!(sim.p.figures().steps_up, 1);
}

#[test]
fn a_transport_that_can_shrink_its_frames_is_asked_to_before_the_level_drops() {
    use ColorLevel::*;
    // 375 kB/s (3 Mbit/s): truecolor frames make 11 a second as they are, 45 at a quarter.
    let mut sim = Sim::new(TrueColor);
    sim.could_shrink = Some(0.25);
    assert_eq!(sim.run(375_000.0, 20.0), [TrueColor]);
    assert!((sim.ratio - 0.25).abs() < 1e-9);
    assert_eq!(sim.p.figures().steps_down, 0);
    // Shrunk frames that still do not fit: the level drops after all.
    let mut sim = Sim::new(TrueColor);
    sim.could_shrink = Some(0.8);
    // (Later tries of truecolor on the quiet link fail the same way.)
    let levels = sim.run(375_000.0, 10.0);
    assert_eq!(levels[..2], [TrueColor, Ansi256], "{levels:?}");
    assert!(
        (sim.ratio - 1.0).abs() < 1e-9,
        "not shrunk when it would not do"
    );
}

#[test]
fn a_level_measured_as_it_went_is_judged_at_the_size_frames_go_now() {
    use ColorLevel::*;
    let mut sim = Sim::new(TrueColor);
    assert_eq!(sim.run(375_000.0, 4.0), [TrueColor, Ansi256]);
    // The transport shrinks frames from now on (a browser's compression): truecolor,
    // measured at 33 kB, goes at a quarter of that, which the link carries.
    // Up as soon as the hold after the step allows (a try on a quiet link would wait for a
    // whole hold of quiet first), and it holds.
    sim.ratio = 0.25;
    // Only the measured speed may say so here: no try for a link that stayed quiet.
    (sim.p.quiet_since, sim.p.quiet_frames) = (None, 0);
    assert_eq!(sim.run(375_000.0, 3.0), [Ansi256, TrueColor]);
    assert_eq!(sim.run(375_000.0, 30.0), [TrueColor]);
    assert_eq!(sim.p.figures().steps_up, 1);
}

#[test]
fn a_step_up_that_does_not_hold_makes_the_next_wait_longer() {
    let mut sim = Sim::new(ColorLevel::TrueColor);
    sim.run(400_000.0, 2.0);
    // As if the last step had gone up to truecolor and its frames were then held up.
    let (p, t) = (&mut sim.p, sim.now);
    let hold = p.up_hold;
    p.last_up = Some((ColorLevel::TrueColor, t));
    p.settled = SETTLE_FRAMES;
    assert_eq!(
        p.step(ColorLevel::TrueColor, t, None),
        Some(Step::Down(ColorLevel::Ansi256))
    );
    assert_eq!(p.up_hold, hold * 2);
}

#[test]
fn a_frame_the_client_has_not_answered_for_holds_the_next_and_counts_as_held_up() {
    let t = Instant::now();
    let mut p = LinkPacer::new(PERIOD, ColorLevel::Ansi256);
    let acked = sample(0, 10_000_000);
    p.sent(0, 10_000, ColorLevel::Ansi256, t);
    assert!(p.clear(10_000, Some(&acked), true, t + PERIOD));
    // The next frame, a period later (moving): written and acknowledged by the kernel (the
    // hop to a balancer), not yet answered by the client.
    p.sent(10_000, 20_000, ColorLevel::Ansi256, t + PERIOD);
    assert!(!p.clear(30_000, Some(&acked), false, t + 2 * PERIOD));
    assert!(p.clear(30_000, Some(&acked), true, t + 3 * PERIOD));
    assert_eq!(p.take_waited(), Some(PERIOD));
    // 20 kB in two periods: the link measured end to end, not the fast first hop.
    let rate = p.measured().expect("measured");
    let want = 20_000.0 / (2.0 * PERIOD.as_secs_f64());
    assert!((rate - want).abs() < 1_000.0, "{rate} against {want}");
}

#[test]
fn a_link_at_the_edge_does_not_flap() {
    use ColorLevel::*;
    // 140 kB/s: 256-colour frames (8 kB) still make 17 a second, truecolor ones 4.
    assert_eq!(
        Sim::new(TrueColor).run(140_000.0, 60.0),
        [TrueColor, Ansi256]
    );
    // 300 kB/s: 256-colour frames never wait, so now and then truecolor is tried; each
    // failed try doubles the wait before the next (5, 10, 20, 40 s …).
    let mut sim = Sim::new(TrueColor);
    let levels = sim.run(300_000.0, 120.0);
    assert_eq!(levels.last(), Some(&Ansi256), "{levels:?}");
    let f = sim.p.figures();
    assert!(f.steps_up <= 5, "{levels:?}");
    assert_eq!(f.steps_down, f.steps_up + 1, "{levels:?}");
}

#[test]
fn a_link_that_keeps_up_is_asked_every_few_frames_until_it_holds_one_up() {
    let t = Instant::now();
    let mut p = LinkPacer::new(PERIOD, ColorLevel::Ansi256);
    let mut wire = 0;
    let mut asked = 0;
    for i in 0..(KEPT_UP_STREAK + 4 * ASK_EVERY) {
        let now = t + PERIOD * i;
        p.sent(wire, 8_000, ColorLevel::Ansi256, now);
        wire += 8_000;
        let ask = p.needs_sample(wire);
        asked += u32::from(ask);
        let s = sample(0, 1_000_000);
        assert!(p.clear(wire, ask.then_some(&s), true, now + PERIOD / 2));
    }
    assert_eq!(
        asked,
        KEPT_UP_STREAK + 4,
        "every frame, then one in {ASK_EVERY}"
    );
    // Held up once: asked every frame again.
    p.sent(wire, 8_000, ColorLevel::Ansi256, t);
    wire += 8_000;
    while !p.needs_sample(wire) {
        assert!(p.clear(wire, None, true, t));
        p.sent(wire, 8_000, ColorLevel::Ansi256, t);
        wire += 8_000;
    }
    assert!(!p.clear(wire, Some(&sample(8_000, 1_000_000)), true, t));
    assert!(p.clear(wire, Some(&sample(0, 1_000_000)), true, t + PERIOD));
    p.sent(wire, 8_000, ColorLevel::Ansi256, t + PERIOD);
    assert!(p.needs_sample(wire + 8_000));
}

#[test]
fn one_late_frame_is_a_hiccup_and_three_lately_a_slow_link() {
    use ColorLevel::TrueColor;
    let mut p = LinkPacer::new(PERIOD, TrueColor);
    let (mut wire, mut now) = (0, Instant::now());
    // 30 kB moving frames; `late` ones are acked 80 ms after they went (375 kB/s, 12 a second),
    // the others at once.
    let mut frame = |p: &mut LinkPacer, late: bool| {
        p.sent(wire, 30_000, TrueColor, now);
        wire += 30_000;
        now += PERIOD;
        if late {
            assert!(!p.clear(wire, Some(&sample(30_000, 0)), true, now));
            now += Duration::from_millis(80) - PERIOD;
        }
        assert!(p.clear(wire, Some(&sample(0, 0)), true, now));
        p.step(TrueColor, now, None)
    };
    for _ in 0..10 {
        assert_eq!(frame(&mut p, false), None);
    }
    assert_eq!(frame(&mut p, true), None, "one late frame: a hiccup");
    assert_eq!(frame(&mut p, false), None);
    assert_eq!(frame(&mut p, true), None);
    assert_eq!(
        frame(&mut p, true),
        Some(Step::Down(ColorLevel::Ansi256)),
        "three late frames in 5 s: the link is slow"
    );
}

#[test]
fn a_status_line_says_nothing_of_how_frames_go_on_the_wire() {
    use ColorLevel::TrueColor;
    let mut p = LinkPacer::new(PERIOD, TrueColor);
    let t = Instant::now();
    // Two compressed view frames (33 kB as 9 kB), then a 60-byte status line that deflate
    // hardly shrinks.
    p.sent(0, 33_000, TrueColor, t);
    p.sent(9_000, 33_000, TrueColor, t + PERIOD);
    p.sent(18_000, 60, TrueColor, t + 2 * PERIOD);
    assert!((p.wire_ratio - 9.0 / 33.0).abs() < 1e-9);
    p.sent(18_055, 33_000, TrueColor, t + 3 * PERIOD);
    assert!((p.wire_ratio - 9.0 / 33.0).abs() < 1e-9, "{}", p.wire_ratio);
}
