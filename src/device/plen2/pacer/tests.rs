//! The pacer's own tests: how it paces, and what replies teach it.

use super::*;

fn pacer(mode: PacingMode) -> Pacer {
    Pacer::new(mode, Pacing::default(), 2_000_000)
}

#[test]
fn a_write_that_leaves_late_moves_every_later_prediction() {
    let t0 = Instant::now();
    let mut pacer = pacer(PacingMode::Fast);
    assert_eq!(pacer.room(t0, false), 24);
    let reads: Vec<Instant> = (0..24).map(|_| pacer.place(t0, Duration::ZERO)).collect();
    pacer.handed(t0, 24);
    let on_time = pacer.next_room(t0);
    assert_eq!(on_time, reads[23]);
    // The write really left 8 ms later than planned.
    let late = Duration::from_millis(8);
    assert_eq!(pacer.written(t0 + late), Some((t0, late)));
    assert_eq!(pacer.next_room(t0), on_time + late, "the next batch waits for the robot to read this one");
    assert_eq!(pacer.room(on_time, false), 0, "on the old schedule the ring is still full");
    assert_eq!(pacer.room(on_time + late, false), 24);
    // A write on time changes nothing.
    pacer.place(on_time + late, Duration::ZERO);
    pacer.handed(on_time + late, 1);
    assert_eq!(pacer.written(on_time + late), None);
}

#[test]
fn the_official_pacing_is_32_bytes_then_50_ms() {
    let t0 = Instant::now();
    let mut pacer = pacer(PacingMode::Safe);
    assert_eq!(pacer.room(t0, false), 32);
    for _ in 0..32 {
        pacer.place(t0, Duration::ZERO);
    }
    pacer.handed(t0, 32);
    assert_eq!(pacer.room(t0 + Duration::from_millis(49), false), 0);
    assert!(pacer.room(t0 + Duration::from_millis(49), true) > 0, "a STOP does not wait for the pause");
    assert_eq!(pacer.room(t0 + SAFE_PAUSE, false), 32);
}

#[test]
fn a_slow_smooth_reply_is_a_slower_line_and_a_hiccup_is_not_a_burst() {
    let t0 = Instant::now();
    let mut pacer = pacer(PacingMode::Adaptive);
    // 64-byte pieces every 5.6 ms: a 115200-baud line, smooth.
    pacer.watch_reply(t0, t0);
    for piece in 0..30u32 {
        pacer.reply_bytes(t0 + Duration::from_micros(5_556) * piece, 64);
    }
    pacer.reply_ended();
    let widened = pacer.poll_widened().unwrap();
    assert!(matches!(widened.reason, WidenReason::Slow { bytes_per_s } if (11_400..11_600).contains(&bytes_per_s)));
    assert_eq!(pacer.window(), None, "no bursts: no window");
    // A clean reply with one 6 ms hiccup before a single packet: not a clump.
    pacer.watch_reply(t0, t0);
    pacer.reply_bytes(t0, 64);
    pacer.reply_bytes(t0 + Duration::from_millis(6), 64);
    pacer.reply_ended();
    assert_eq!(pacer.poll_widened(), None);
}

#[test]
fn a_clumpy_reply_widens_the_adaptive_pacer_and_not_the_fast_one() {
    for mode in [PacingMode::Adaptive, PacingMode::Fast] {
        let t0 = Instant::now();
        let mut pacer = pacer(mode);
        pacer.watch_reply(t0, t0);
        for event in 0..3u32 {
            // A Bluetooth bridge's events: 1,464 bytes each, 15 ms apart.
            pacer.reply_bytes(t0 + Duration::from_millis(15) * event, 1464);
        }
        pacer.reply_ended();
        if mode == PacingMode::Adaptive {
            let widened = pacer.poll_widened().unwrap();
            assert_eq!(widened.reason, WidenReason::Bursts { gap: Duration::from_millis(15) });
            assert_eq!(widened.window, Duration::from_micros(19_750));
            assert!(widened.to_string().contains("bursts up to 15.0 ms apart"), "{widened}");
            // Now every byte is predicted 19.75 ms late, and at most 56 are in flight.
            assert_eq!(pacer.room(t0, false), 56);
            let reads: Vec<Instant> = (0..56).map(|_| pacer.place(t0, Duration::ZERO)).collect();
            assert!(reads[0] >= t0 + Duration::from_micros(19_750));
            assert_eq!(pacer.room(t0, false), 0);
            assert_eq!(pacer.next_room(t0), reads[0], "one byte read makes room for one");
            assert_eq!(pacer.room(reads[9], false), 10);
        } else {
            assert_eq!(pacer.poll_widened(), None);
            assert_eq!(pacer.window(), None);
        }
    }
}

/// A bridge that hands each reply over whole shows no gap inside it: how
/// late the reply came, beyond the time its bytes need, widens the
/// window as much. A reply on time (USB's 64-byte packets) does not.
#[test]
fn a_reply_that_comes_whole_but_late_widens_the_adaptive_pacer() {
    let t0 = Instant::now();
    let mut late = pacer(PacingMode::Adaptive);
    late.watch_reply(t0, t0);
    // 1,200 bytes, printed by 1.2 ms, handed over at the bridge's event 16 ms after.
    late.reply_bytes(t0 + Duration::from_millis(16), 1200);
    late.reply_ended();
    let widened = late.poll_widened().unwrap();
    assert_eq!(widened.reason, WidenReason::Late { delay: Duration::from_micros(14_800) });
    assert_eq!(widened.window, Duration::from_micros(14_800 + 3_700 + 1_000));
    assert!(widened.to_string().contains("replies arrive up to 14.8 ms late"), "{widened}");

    let mut clean = pacer(PacingMode::Adaptive);
    clean.watch_reply(t0, t0);
    for packet in 0..20u32 {
        clean.reply_bytes(t0 + Duration::from_micros(64) * (packet + 1), 64);
    }
    clean.reply_ended();
    assert_eq!((clean.poll_widened(), clean.window()), (None, None), "on time");
}

/// One getter's reply, 80 bytes, sent at `sent`, arriving whole at `first`.
fn answered(pacer: &mut Pacer, sent: Instant, first: Instant) {
    pacer.watch_reply(sent, sent);
    pacer.reply_bytes(first, 80);
    pacer.reply_ended();
}

/// Short getters' round trips on a bridge: two back to back agree (30 ms):
/// two events each, 15 ms apart. The window then follows the last few
/// replies: one held up 40 ms by a busy host widens it, four on time
/// narrow it again.
#[test]
fn round_trips_teach_a_bridges_events_and_the_window_narrows_again() {
    let ms = Duration::from_millis;
    let t0 = Instant::now();
    let mut pacer = pacer(PacingMode::Adaptive);
    answered(&mut pacer, t0, t0 + ms(22));
    answered(&mut pacer, t0 + ms(22), t0 + ms(52));
    assert_eq!(pacer.interval(), None, "one round trip is no agreement");
    answered(&mut pacer, t0 + ms(52), t0 + ms(82));
    assert_eq!(pacer.interval(), Some(ms(15)));
    assert!(!pacer.wants_round_trip());
    let learned = std::iter::from_fn(|| pacer.poll_widened()).last().unwrap();
    assert_eq!(learned.reason, WidenReason::Events { interval: ms(15) });
    assert_eq!(pacer.window(), Some(ms(15) + ms(15) / 2 + ms(2)));
    assert!(learned.to_string().contains("connection events 15.0 ms apart"), "{learned}");

    // A reply held up by a busy host: 40 ms more than an event's wait.
    let mut sent = t0 + ms(200);
    answered(&mut pacer, sent, sent + ms(55));
    let own = FASTEST_REPLY_BYTE * 80;
    let held = ms(40) - own;
    assert_eq!(pacer.window(), Some(held + held / 2 + ms(2)));
    for _ in 0..4 {
        sent += ms(100);
        answered(&mut pacer, sent, sent + ms(30));
    }
    assert_eq!(pacer.window(), Some(ms(15) + ms(15) / 2 + ms(2)), "narrowed again");
}

/// A busy host blurs round trips: one taken in late makes the next look
/// quicker (27 ms of 30). The interval is taken from the longest round trip
/// that agrees with the others: too long only paces more slowly.
#[test]
fn round_trips_blurred_by_a_busy_host_are_read_safely() {
    let ms = Duration::from_millis;
    let t0 = Instant::now();
    let mut blurred = pacer(PacingMode::Adaptive);
    answered(&mut blurred, t0, t0 + ms(22));
    answered(&mut blurred, t0 + ms(22), t0 + ms(49));
    answered(&mut blurred, t0 + ms(49), t0 + ms(79));
    assert_eq!(blurred.interval(), Some(ms(15)), "half the longest agreeing round trip (30 ms), not of 27");
    // Round trips that disagree teach nothing: a line's, late by chance.
    let mut late = pacer(PacingMode::Adaptive);
    answered(&mut late, t0, t0 + ms(12));
    answered(&mut late, t0 + ms(12), t0 + ms(31));
    answered(&mut late, t0 + ms(31), t0 + ms(58));
    assert_eq!(late.interval(), None);
}
