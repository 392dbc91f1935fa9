//! The PLEN2 driver's tests: a getter's timeout, resync, and STOP dropping what is queued.

use super::*;
use crate::protocol::plen2::{MotionFrame, MotionHeader, parse_commands};

fn getter(driver: &mut Plen2Driver, now: Instant) -> crossbeam_channel::Receiver<Result<Vec<u8>, ReplyError>> {
    let (reply, outcome) = crossbeam_channel::bounded(1);
    driver.handle_command(now, Plen2Command::Get { command: Command::GetVersion, reply, news: None });
    while driver.poll_transmit(now).is_some() {}
    outcome
}

#[test]
fn silence_ends_a_getter_with_its_timeout_and_chatter_cannot_extend_it() {
    let options = Plen2Options { reply_timeout: Duration::from_millis(300), ..Plen2Options::default() };
    let t0 = Instant::now();
    let mut driver = Plen2Driver::new(options);
    let silent = getter(&mut driver, t0);
    let deadline = driver.poll_timeout().unwrap();
    assert!(deadline - t0 < Duration::from_millis(301), "read, then 300 ms: {:?}", deadline - t0);
    driver.handle_timeout(deadline);
    assert_eq!(silent.try_recv(), Ok(Err(ReplyError::Timeout { timeout_ms: 300 })));

    // A byte every 100 ms, forever, none of them a reply: the first one fixed the end.
    let t1 = deadline;
    let chatter = getter(&mut driver, t1);
    let mut at = t1;
    let mut bytes = 0;
    let ended = loop {
        at += Duration::from_millis(100);
        if let Some(due) = driver.poll_timeout().filter(|due| *due <= at) {
            driver.handle_timeout(due);
            break due;
        }
        driver.handle_input(at, b"\x07");
        bytes += 1;
        assert!(at - t1 < Duration::from_secs(2), "never ended");
    };
    // The first byte at 100 ms; <VI's longest reply is 512 bytes, 2.6 ms at 2 Mbaud; then 300 ms.
    assert_eq!(ended - t1, Duration::from_millis(400) + Duration::from_micros(2_560));
    assert_eq!(chatter.try_recv(), Ok(Err(ReplyError::NotThisProtocol { bytes })));
}

/// Whatever prefix of a command reached the firmware before bytes were
/// lost, the resync bytes end it and the next command is read cleanly.
#[test]
fn resync_ends_any_partial_command() {
    let header = MotionHeader {
        slot: 9,
        name: *b"Walk                ",
        loop_on: true,
        loop_begin: 1,
        loop_end: 2,
        loop_count: 3,
        jump_on: true,
        jump_slot: 4,
        frame_count: 5,
    };
    let frame = MotionFrame { slot: 9, index: 0, transition_ms: 100, values: [0x111; 24] };
    let commands = [
        Command::Header(header),
        Command::Frame(Box::new(frame)),
        Command::SetAngle { device: 14, angle: 1000 },
        Command::SetDiff { device: 4, diff: -100 },
        Command::PlayMotion { slot: 7 },
    ];
    for command in commands {
        let ascii = command.to_ascii();
        for cut in 1..ascii.len() {
            let mut bytes = ascii.as_bytes()[..cut].to_vec();
            bytes.extend_from_slice(RESYNC);
            bytes.extend_from_slice(b"<VI");
            let parsed = parse_commands(&bytes);
            assert_eq!(parsed.last(), Some(&Ok(Command::GetVersion)), "{ascii} cut at {cut}: {parsed:?}");
            assert!(parsed[..parsed.len() - 1].iter().all(Result::is_err), "{ascii} cut at {cut}: {parsed:?}");
        }
    }
}

/// A play, a play list's start and a pose queued a moment before STOP
/// (here behind a getter whose reply is still coming, as behind a slow
/// or bursty link) never go out after it: STOP drops them, tells their
/// waiters they were not sent, and what reaches the robot after the
/// command on the wire is STOP's own `#RI` and `$HP` only.
#[test]
fn stop_drops_every_command_still_queued_and_nothing_that_moves_the_robot_goes_out_after_it() {
    let t0 = Instant::now();
    let mut driver = Plen2Driver::new(Plen2Options::default());
    let waiting = getter(&mut driver, t0);
    let (done, played) = crossbeam_channel::bounded(1);
    driver.handle_command(t0, Plen2Command::Send { command: Command::PlayMotion { slot: 3 }, done: Some(done) });
    driver.handle_command(t0, Plen2Command::Send { command: Command::Pop, done: None });
    let (reply, asked) = crossbeam_channel::bounded(1);
    driver.handle_command(t0, Plen2Command::Get { command: Command::GetMotion { slot: 1 }, reply, news: None });
    driver.handle_command(t0, Plen2Command::LiveAngles(vec![(2, 300)]));
    driver.handle_command(t0, Plen2Command::Stop);
    // Everything the driver hands to the port from now on, for a long while.
    let mut sent = Vec::new();
    let mut at = t0;
    for _ in 0..200 {
        while let Some(bytes) = driver.poll_transmit(at) {
            sent.extend(bytes);
        }
        at += Duration::from_millis(5);
        if let Some(due) = driver.poll_timeout().filter(|due| *due <= at) {
            driver.handle_timeout(due);
        }
    }
    let commands: Vec<Command> = parse_commands(&sent).into_iter().filter_map(Result::ok).collect();
    assert_eq!(commands, [Command::ResetInterpreter, Command::HomePosition], "{}", String::from_utf8_lossy(&sent));
    assert_eq!(played.try_recv(), Ok(Err(ReplyError::Stopped)), "the play's waiter is told");
    assert_eq!(asked.try_recv(), Ok(Err(ReplyError::Stopped)), "the getter's too");
    // The getter already on the wire is STOP's to let end, not to drop.
    assert!(!matches!(waiting.try_recv(), Ok(Err(ReplyError::Stopped))));
}

/// The owner sends STOP and closes the link at once (the command line's
/// Ctrl-C, a show closing): whichever the I/O thread sees first, `#RI` and
/// `$HP` still go out. (A coin toss each time: twenty in a row.)
#[test]
fn a_stop_sent_just_before_the_close_still_goes_out() {
    for _ in 0..20 {
        let (mut robot, ours) = crate::link::Connection::memory_pair();
        let link =
            crate::link::spawn(ours, Plen2Driver::new(Plen2Options::default()), crate::link::no_waker()).unwrap();
        link.commands().send(Plen2Command::Stop).unwrap();
        link.close();
        let mut heard = Vec::new();
        robot.reader_mut().read_to_end(&mut heard).unwrap();
        let heard = String::from_utf8_lossy(&heard);
        assert!(heard.contains("#RI") && heard.contains("$HP"), "{heard:?}");
    }
}
