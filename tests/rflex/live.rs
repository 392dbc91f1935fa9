//! The rFLEX handle against the in-process emulated base: telemetry from every
//! report, bump panels and joystick, and a dropped handle that leaves the base
//! stopped and braked.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::sync::Arc;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;
use servo_studio::device::rflex::RflexBase;
use servo_studio::link::Waker;
use servo_studio::protocol::rflex::B21R;
use servo_studio::sim::{
    BaseState, RflexSim, RflexSimCommand, RflexSimConfig, RflexSimEvent, SimHandle, spawn_in_memory,
};

type Sim = SimHandle<RflexSimCommand, RflexSimEvent>;

fn connect() -> (Sim, RflexBase, Receiver<()>) {
    let (sender, woken) = crossbeam_channel::unbounded();
    let waker: Waker = Arc::new(move || {
        let _ = sender.send(());
    });
    let (sim, connection) = spawn_in_memory(RflexSim::new(RflexSimConfig::default()), waker.clone()).unwrap();
    let base = RflexBase::over(connection, B21R, waker).unwrap();
    (sim, base, woken)
}

fn until(base: &mut RflexBase, woken: &Receiver<()>, what: &str, done: impl Fn(&RflexBase) -> bool) {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        base.pump(Instant::now());
        if done(base) {
            return;
        }
        assert!(woken.recv_deadline(deadline).is_ok(), "timed out waiting for {what}");
    }
}

fn inspect(sim: &Sim) -> BaseState {
    let (reply, state) = crossbeam_channel::bounded(1);
    sim.command(RflexSimCommand::Inspect(reply));
    state.recv_timeout(Duration::from_secs(10)).unwrap()
}

#[test]
fn a_full_set_of_reports_becomes_telemetry_in_si_units() {
    let (sim, mut base, woken) = connect();
    base.start(true);
    until(&mut base, &woken, "a full set", |base| base.telemetry.complete());
    let telemetry = &base.telemetry;
    let state = inspect(&sim);
    assert!((telemetry.battery_volts.unwrap() - state.battery_volts).abs() < 0.02);
    assert_eq!(telemetry.brake, Some(true), "the base starts braked");
    assert_eq!(telemetry.sonar_m.len(), 48, "a B21r's body and base rings");
    assert_eq!(telemetry.bumpers.len(), 14, "its 14 bump panels");
    assert_eq!(telemetry.checksum_failures, 0);

    sim.command(RflexSimCommand::Bump { panel: 2, corners: 0b0101 });
    sim.command(RflexSimCommand::Joystick { x: -12, y: 34, buttons: 0b10 });
    until(&mut base, &woken, "the pressed panel and the joystick", |base| {
        base.telemetry.pressed() == [servo_studio::device::rflex::Bump::Panel { panel: 2, corners: 0b0101 }]
            && base.telemetry.bumpers.get(&0x42) == Some(&0b0101)
            && base.telemetry.joystick == Some((-12, 34, 0b10))
    });
}

#[test]
fn odometry_follows_the_base_as_it_drives() {
    let (sim, mut base, woken) = connect();
    base.start(false);
    base.set_brake(false);
    base.drive(0.5, 0.0, 2.0);
    until(&mut base, &woken, "half a metre", |base| base.telemetry.pose.x_m > 0.5);
    let state = inspect(&sim);
    assert!((base.telemetry.pose.x_m - state.x_m).abs() < 0.1, "{:?} vs {state:?}", base.telemetry.pose);
    assert!(base.telemetry.pose.y_m.abs() < 1e-6);
    assert!(!base.telemetry.path.is_empty());
    assert!((base.telemetry.speed_m_per_s - 0.5).abs() < 0.01, "measured {}", base.telemetry.speed_m_per_s);
}

#[cfg(unix)]
#[test]
fn dropping_the_handle_stops_the_base_and_sets_its_brake() {
    // Behind a pseudo-terminal, the base outlives its client, as a real one does.
    let (sender, woken) = crossbeam_channel::unbounded();
    let waker: Waker = Arc::new(move || {
        let _ = sender.send(());
    });
    let sim = servo_studio::sim::spawn_pty(RflexSim::new(RflexSimConfig::default()), waker.clone()).unwrap();
    let port = servo_studio::link::PortName::parse(&sim.port_name).unwrap();
    let settings = servo_studio::device::line_settings(servo_studio::project::Family::Rflex);
    let mut base = RflexBase::over(servo_studio::link::open(&port, &settings).unwrap(), B21R, waker).unwrap();
    base.start(false);
    base.set_brake(false);
    base.drive(0.3, 0.2, 0.5);
    until(&mut base, &woken, "motion", |base| base.telemetry.speed_m_per_s > 0.05);
    drop(base); // the window closed, or the program ended
    // Every byte of the stop and the brake was written before the drop
    // returned; the emulated base reads them on its own thread, whenever a
    // loaded machine runs it: asked again at each of its wakes (or every
    // 50 ms), for up to 10 s.
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut state = inspect(&sim);
    while !state.braked && Instant::now() < deadline {
        let _ = woken.recv_timeout(Duration::from_millis(50));
        state = inspect(&sim);
    }
    assert!(state.braked, "{state:?}");
    assert_eq!(state.target_speed_m_per_s, 0.0);
    assert_eq!(state.speed_m_per_s, 0.0, "braked: not moving");
}
