//! Tests of the emulated rFLEX base.

use super::*;

fn sim() -> (RflexSim, Instant) {
    let mut sim = RflexSim::new(RflexSimConfig::default());
    let t0 = Instant::now();
    sim.tick(t0);
    (sim, t0)
}

#[test]
fn a_braked_base_does_not_move_and_a_released_one_ramps_at_its_acceleration() {
    let (mut sim, t0) = sim();
    let [forward, turn] = B21R.drive(0.5, 0.0, 0.5);
    sim.handle(t0, forward.clone());
    sim.handle(t0, turn.clone());
    sim.tick(t0 + Duration::from_millis(400));
    assert_eq!(sim.state().distance_m, 0.0, "braked");
    sim.handle(t0, Command::BrakeRelease);
    let t1 = t0 + Duration::from_millis(400);
    sim.handle(t1, forward);
    sim.handle(t1, turn);
    sim.tick(t1 + Duration::from_millis(400));
    let state = sim.state();
    assert!((state.speed_m_per_s - 0.2).abs() < 1e-3, "{state:?}");
    assert!((state.distance_m - 0.04).abs() < 1e-3, "½·a·t² = 0.04 m: {state:?}");
}

#[test]
fn the_dead_man_stops_a_base_whose_commands_stop() {
    let (mut sim, t0) = sim();
    sim.handle(t0, Command::BrakeRelease);
    let [forward, _] = B21R.drive(0.5, 0.0, 0.5);
    sim.handle(t0, forward);
    assert_eq!(sim.poll_timeout(), Some(t0 + Duration::from_millis(500)));
    sim.handle_timeout(t0 + Duration::from_millis(500));
    assert!(sim.events.contains(&RflexSimEvent::DeadManStop));
    sim.tick(t0 + Duration::from_secs(2));
    assert_eq!(sim.state().speed_m_per_s, 0.0);
}

#[test]
fn a_wall_stops_the_base_and_presses_its_front_panel() {
    let (mut sim, t0) = sim();
    sim.handle(t0, Command::BrakeRelease);
    let mut t = t0;
    for _ in 0..100 {
        // Keep the dead-man fed: 1 m/s straight at the wall 2.1 m ahead.
        sim.handle(t, B21R.drive(1.0, 0.0, 5.0)[0].clone());
        t += Duration::from_millis(100);
        sim.tick(t);
    }
    let state = sim.state();
    assert!((state.x_m - (2.1 - B21R.layout.body_radius_m)).abs() < 1e-9, "{state:?}");
    assert_eq!(state.speed_m_per_s, 0.0);
    assert_eq!(sim.bumpers[0], 0b0011, "the front panel is pressed");
    // Backing away releases it.
    sim.handle(t, B21R.drive(-0.5, 0.0, 5.0)[0].clone());
    sim.tick(t + Duration::from_millis(300));
    assert_eq!(sim.bumpers[0], 0);
}

#[test]
fn sonars_measure_the_room_from_their_mounts_along_their_bearings() {
    let (sim, _) = sim();
    let range = |id: u8| sim.sonar_range(&B21R.layout.transducer(id).unwrap());
    // A B21r in the middle of a 4.2 × 2.8 m room, facing +x. Its base ring's
    // transducer 40 (id 177) faces ahead from 0.26 m: 2.1 − 0.26 = 1.84 m (2715.8 units);
    // transducer 34 (id 145) faces left: 1.4 − 0.26 = 1.14 m (1682.6); transducer 28
    // (id 113) faces behind: 1.84 m again.
    assert_eq!(range(177), 2716);
    assert_eq!(range(145), 1683);
    assert_eq!(range(113), 2716);
    // Body transducer 0 (id 0) faces 172.5° from (−0.2479, 0.0326): the back wall is
    // (2.1 − 0.2479) / cos 7.5° = 1.8681 m away (2757.3 units).
    assert_eq!(range(0), 2757);
    // A Magellan: transducer 11 (id 19) faces ahead from 0.20 m, 1474 units a metre: 1.9 m.
    let magellan =
        RflexSim::new(RflexSimConfig { conversion: crate::protocol::rflex::MAGELLAN, ..RflexSimConfig::default() });
    assert_eq!(magellan.sonar_range(&crate::protocol::rflex::MAGELLAN.layout.transducer(19).unwrap()), 2801);
}
