//! Live operations against the in-process emulated board.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use servo_studio::device::servo::{OpError, ServoBoard, ServoEvent, ServoImage, SessionConfig};
use servo_studio::link::{LinkEvent, no_waker};
use servo_studio::protocol::servo::{ALL_SERVOS, AngleUnit, ButtonEvent, ServoMove, ServoSwitches};
use servo_studio::sim::{ServoSim, SimCommand, SimConfig, SimEvent, SimHandle, spawn_in_memory};

fn start() -> (SimHandle, ServoBoard) {
    let image = ServoImage::from_project(&common::rich_project()).unwrap();
    let (sim, connection) = spawn_in_memory(ServoSim::new(SimConfig::default(), image), no_waker()).unwrap();
    let board = ServoBoard::over(connection, SessionConfig::default(), no_waker()).unwrap();
    (sim, board)
}

/// Waits (on the board's own event channel, with a deadline) until it has handled `count` messages.
fn wait_handled(sim: &SimHandle, count: usize) {
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut seen = 0;
    while seen < count {
        match sim.events().recv_deadline(deadline) {
            Ok(LinkEvent::Driver(SimEvent::Handled(_))) => seen += 1,
            Ok(_) => {}
            Err(_) => panic!("the board handled only {seen} of {count} messages"),
        }
    }
}

#[test]
fn status_queries() {
    let (_sim, board) = start();
    let requester = board.requester();
    assert_eq!(requester.project_id().unwrap(), i32::MAX);
    assert_eq!(requester.battery_permil().unwrap(), 870);
    let (free, total) = requester.memory().unwrap();
    assert!(free > 0 && total == Some(256 * 1024) && free < 256 * 1024, "{free} {total:?}");
    assert_eq!(requester.query_servos(ALL_SERVOS).unwrap().len(), 60);
    assert_eq!(requester.set_angle_unit(3, AngleUnit::Adc).unwrap(), AngleUnit::Adc);
}

#[test]
fn a_live_move_reaches_its_angle() {
    let (sim, board) = start();
    let requester = board.requester();
    requester.move_servos(vec![ServoMove { servo_id: 5, degree: -75, interval_10ms: 0 }]).unwrap();
    wait_handled(&sim, 1);
    assert_eq!(requester.query_servos(5).unwrap()[0].angle, -75);
}

#[test]
fn running_a_stored_action_and_macro() {
    let (sim, board) = start();
    let requester = board.requester();
    // Action i32::MAX moves servo 59 to -1 at once.
    requester.run_action(i32::MAX).unwrap();
    wait_handled(&sim, 1);
    assert_eq!(requester.query_servos(59).unwrap()[0].angle, -1);
    requester.run_macro(100).unwrap();
    let error = requester.run_macro(12345).unwrap_err();
    assert!(matches!(error, OpError::Refused { .. }), "{error:?}");
}

#[test]
fn torque_off_then_teach_by_hand() {
    let (sim, board) = start();
    let requester = board.requester();
    let released = ServoSwitches { servo_id: ALL_SERVOS, is_start: true, is_hold: false };
    assert_eq!(requester.set_servo_switches(released).unwrap(), released);
    sim.command(SimCommand::TurnByHand { servo_id: 2, angle: 44 });
    // The command and the query travel different channels: ask until the turn shows.
    let deadline = Instant::now() + Duration::from_secs(10);
    while requester.query_servos(2).unwrap()[0].angle != 44 {
        assert!(Instant::now() < deadline, "the hand turn never showed");
        std::thread::yield_now();
    }
    assert!(!requester.query_servos(2).unwrap()[0].is_hold);
}

#[test]
fn subscribed_button_events_arrive() {
    let (sim, board) = start();
    board.requester().subscribe_buttons(true).unwrap();
    sim.command(SimCommand::Button { button_id: 0x8000_0001, event: ButtonEvent::LongPress });
    let event = board.events().recv_timeout(Duration::from_secs(10)).unwrap();
    assert_eq!(event, LinkEvent::Driver(ServoEvent::Button { button_id: 0x8000_0001, event: ButtonEvent::LongPress }));
}

#[test]
fn dropping_the_board_closes_the_link() {
    let (sim, board) = start();
    let requester = board.requester();
    drop(board);
    let error = requester.project_id().unwrap_err();
    assert!(error.to_string().contains("the link"), "{error}");
    // The emulated board sees its client go.
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        match sim.events().recv_deadline(deadline) {
            Ok(LinkEvent::Disconnected { .. }) => break,
            Ok(_) => {}
            Err(_) => panic!("the board never saw the client go"),
        }
    }
}
