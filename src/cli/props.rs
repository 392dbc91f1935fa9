//! Every number the command line takes, fed extreme text: refused while it is
//! parsed, or within its bounds (and safe to compute with).

use super::*;
use proptest::prelude::*;

/// Text a user (or a script gone wrong) may type where a number goes.
fn number_text() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|value| value.to_string()),
        any::<i64>().prop_map(|value| value.to_string()),
        any::<u64>().prop_map(|value| value.to_string()),
        prop::sample::select(vec![
            "1e20",
            "-1e20",
            "1.8e19",
            "NaN",
            "inf",
            "-inf",
            "1e-320",
            "-0",
            "0",
            "18446744073709551616",
            "99999999999999999999999",
            "-1",
            " 5 ",
            "0x10",
            "",
        ])
        .prop_map(str::to_string),
    ]
}

/// Every numeric option, where it is given.
const NUMERIC: &[&[&str]] = &[
    &["rflex", "drive", "--port", "p", "--speed", "0.1", "--seconds"],
    &["rflex", "drive", "--port", "p", "--seconds", "1", "--speed"],
    &["rflex", "drive", "--port", "p", "--seconds", "1", "--speed", "0", "--turn"],
    &["rflex", "drive", "--port", "p", "--seconds", "1", "--speed", "0", "--accel"],
    &["rflex", "teleop", "--port", "p", "--gamepad", "g", "--speed"],
    &["rflex", "teleop", "--port", "p", "--gamepad", "g", "--turn"],
    &["rflex", "teleop", "--port", "p", "--gamepad", "g", "--accel"],
    &["rflex", "teleop", "--port", "p", "--gamepad", "g", "--dead-zone"],
    &["board", "info", "--port", "p", "--timeout-ms"],
    &["board", "info", "--port", "p", "--baud"],
    &["sim", "--baud"],
    &["sim", "--turnaround-ms"],
    &["sim", "--memory"],
    &["trajectory", "f.json", "--out", "o.csv", "--action", "1", "--seconds"],
    &["trajectory", "f.json", "--out", "o.csv", "--slot"],
    &["trajectory", "f.json", "--out", "o.csv", "--slot", "1", "--from-slot"],
];

/// What a parsed command holds, checked against the bounds; durations
/// made from it (the arithmetic that panicked) must not panic.
fn within_bounds(command: &CliCommand) -> bool {
    let port_ok = |port: &PortArgs| {
        port.baud.is_none_or(|baud| bounds::BAUD.contains(&baud))
            && port.timeout_ms.is_none_or(|ms| (1..=bounds::MAX_TIMEOUT_MS).contains(&ms))
    };
    match command {
        CliCommand::Rflex { command: rflex::RflexCommand::Drive { base, speed, turn, accel, seconds } } => {
            let _ = bounds::duration(*seconds);
            let _ = std::time::Instant::now() + bounds::duration(*seconds);
            port_ok(&base.port)
                && (0.0..=bounds::MAX_SECONDS).contains(seconds)
                && speed.abs() <= bounds::MAX_SPEED_M_PER_S
                && turn.abs() <= bounds::MAX_TURN_RAD_PER_S
                && *accel > 0.0
                && *accel <= bounds::MAX_ACCEL_M_PER_S2
        }
        CliCommand::Rflex {
            command: rflex::RflexCommand::Teleop { base, speed, turn, accel, dead_zone, axis_range, .. },
        } => {
            let top = bounds::MAX_SPEED_M_PER_S.max(bounds::MAX_TURN_RAD_PER_S);
            let top_ok = |value: &Option<f64>| value.is_none_or(|value| value > 0.0 && value <= top);
            port_ok(&base.port)
                && top_ok(speed)
                && top_ok(turn)
                && *accel > 0.0
                && *accel <= bounds::MAX_ACCEL_M_PER_S2
                && (0.0..=0.9).contains(dead_zone)
                && axis_range.is_none_or(|(min, max)| min < max)
        }
        CliCommand::Board { command: BoardCommand::Info { port } } => port_ok(port),
        CliCommand::Sim { args, .. } => {
            args.baud.is_none_or(|baud| bounds::BAUD.contains(&baud))
                && args.turnaround_ms.is_none_or(|ms| ms <= bounds::MAX_TURNAROUND_MS)
                && args.memory.is_none_or(|bytes| bounds::MEMORY_BYTES.contains(&bytes))
        }
        CliCommand::Trajectory { seconds, slot, from_slot, .. } => {
            let _ = bounds::duration(*seconds).as_secs_f64() * 1000.0 / 32.768;
            *seconds > 0.0
                && *seconds <= bounds::MAX_SECONDS
                && slot.is_none_or(|slot| slot < 90)
                && from_slot.is_none_or(|slot| slot < 90)
        }
        _ => false,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Any text given as an axis range is refused or a range with MIN below MAX.
    #[test]
    fn an_axis_range_is_refused_or_ordered(min in number_text(), max in number_text()) {
        let text = format!("{min}:{max}");
        let line = ["servo-studio", "rflex", "teleop", "--port", "p", "--gamepad", "g", "--axis-range", &text];
        if let Ok(Cli { command: Some(CliCommand::Rflex { command: rflex::RflexCommand::Teleop { axis_range, .. } }) }) =
            Cli::try_parse_from(line)
        {
            prop_assert!(axis_range.is_some_and(|(min, max)| min < max), "{text}: {axis_range:?}");
        }
    }

    /// Any text given to any numeric option is refused or parsed within its bounds.
    #[test]
    fn every_numeric_option_is_refused_or_within_its_bounds(which in 0..NUMERIC.len(), value in number_text()) {
        let args = NUMERIC[which];
        let mut line = vec!["servo-studio"];
        line.extend_from_slice(args);
        line.push(&value);
        match Cli::try_parse_from(&line) {
            Ok(Cli { command: Some(command) }) => prop_assert!(within_bounds(&command), "{line:?} gave {command:?}"),
            Ok(other) => prop_assert!(false, "{line:?} gave {other:?}"),
            Err(error) => prop_assert!(
                matches!(error.kind(), clap::error::ErrorKind::ValueValidation | clap::error::ErrorKind::InvalidValue),
                "{line:?}: {error}"
            ),
        }
    }
}
