//! The echo board's two ends of its one-line protocol: `M <deg>\n` moves the
//! servo, `S\n` stops it; the board answers every move with `E <deg>\n`.
//! [`EchoBoard`] is the emulated board (a [`Driver`] the `sim` runners
//! serve), [`EchoDriver`] the client side.

use std::collections::VecDeque;
use std::time::Instant;

use crate::link::Driver;

/// Reads whole lines out of a byte stream.
#[derive(Debug, Default)]
struct Lines(Vec<u8>);

impl Lines {
    fn push(&mut self, bytes: &[u8]) -> Vec<String> {
        self.0.extend_from_slice(bytes);
        let mut lines = Vec::new();
        while let Some(end) = self.0.iter().position(|byte| *byte == b'\n') {
            let line: Vec<u8> = self.0.drain(..=end).collect();
            lines.push(String::from_utf8_lossy(&line[..end]).into_owned());
        }
        lines
    }
}

/// The degrees a line `<letter> <deg>` carries.
fn degrees(line: &str, letter: char) -> Option<i16> {
    line.strip_prefix(letter)?.trim().parse().ok()
}

/// What the emulated board did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BoardEvent {
    /// Its servo went to this angle.
    Moved(i16),
    /// It was told to stop.
    Stopped,
}

/// The emulated echo board.
#[derive(Debug, Default)]
pub struct EchoBoard {
    lines: Lines,
    out: VecDeque<Vec<u8>>,
    events: VecDeque<BoardEvent>,
}

impl Driver for EchoBoard {
    type Command = ();
    type Event = BoardEvent;

    fn handle_command(&mut self, _now: Instant, (): ()) {}

    fn handle_input(&mut self, _now: Instant, bytes: &[u8]) {
        for line in self.lines.push(bytes) {
            if let Some(deg) = degrees(&line, 'M') {
                self.out.push_back(format!("E {deg}\n").into_bytes());
                self.events.push_back(BoardEvent::Moved(deg));
            } else if line == "S" {
                self.events.push_back(BoardEvent::Stopped);
            }
        }
    }

    fn handle_timeout(&mut self, _now: Instant) {}

    fn handle_disconnect(&mut self, _reason: &str) {}

    fn poll_transmit(&mut self, _now: Instant) -> Option<Vec<u8>> {
        self.out.pop_front()
    }

    fn poll_event(&mut self) -> Option<BoardEvent> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
}

/// What the client asks of the board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EchoCommand {
    /// The servo to this angle.
    Move(i16),
    /// Stop.
    Stop,
}

/// The client side: sends moves and stops, reports each echo.
#[derive(Debug, Default)]
pub struct EchoDriver {
    lines: Lines,
    out: VecDeque<Vec<u8>>,
    echoes: VecDeque<i16>,
}

impl Driver for EchoDriver {
    type Command = EchoCommand;
    type Event = i16;

    fn handle_command(&mut self, _now: Instant, command: EchoCommand) {
        let line = match command {
            EchoCommand::Move(deg) => format!("M {deg}\n"),
            EchoCommand::Stop => "S\n".to_string(),
        };
        self.out.push_back(line.into_bytes());
    }

    fn handle_input(&mut self, _now: Instant, bytes: &[u8]) {
        self.echoes.extend(self.lines.push(bytes).iter().filter_map(|line| degrees(line, 'E')));
    }

    fn handle_timeout(&mut self, _now: Instant) {}

    fn handle_disconnect(&mut self, _reason: &str) {}

    fn poll_transmit(&mut self, _now: Instant) -> Option<Vec<u8>> {
        self.out.pop_front()
    }

    fn poll_event(&mut self) -> Option<i16> {
        self.echoes.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_board_answers_each_move_with_its_angle_even_when_lines_arrive_in_pieces() {
        let now = Instant::now();
        let mut board = EchoBoard::default();
        board.handle_input(now, b"M 3");
        assert_eq!(board.poll_transmit(now), None, "half a line is not a move");
        board.handle_input(now, b"0\nS\nM -45\n");
        assert_eq!(board.poll_transmit(now), Some(b"E 30\n".to_vec()));
        assert_eq!(board.poll_transmit(now), Some(b"E -45\n".to_vec()));
        let events: Vec<_> = std::iter::from_fn(|| board.poll_event()).collect();
        assert_eq!(events, [BoardEvent::Moved(30), BoardEvent::Stopped, BoardEvent::Moved(-45)]);
    }

    #[test]
    fn the_client_writes_the_lines_and_reads_the_echoes() {
        let now = Instant::now();
        let mut client = EchoDriver::default();
        client.handle_command(now, EchoCommand::Move(12));
        client.handle_command(now, EchoCommand::Stop);
        assert_eq!(client.poll_transmit(now), Some(b"M 12\n".to_vec()));
        assert_eq!(client.poll_transmit(now), Some(b"S\n".to_vec()));
        client.handle_input(now, b"E 12\nE x\n");
        assert_eq!(client.poll_event(), Some(12));
        assert_eq!(client.poll_event(), None, "a line that is no echo is skipped");
    }
}
