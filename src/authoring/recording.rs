//! A recorded movement as CSV, in the layout `servo-studio trajectory`
//! writes: a header `t_ms`, then one column per joint or servo by name; one
//! row per sample. Any sample rate is read; [`Recording::resample`] gives the
//! values at the board's own update.

/// The longest recording read, s (an hour: 360,000 servo-board updates).
pub const MAX_SECONDS: f64 = 3600.0;

/// The most values a recording may hold (rows × columns).
pub const MAX_VALUES: usize = 50_000_000;

/// A movement as sampled.
#[derive(Clone, Debug, PartialEq)]
pub struct Recording {
    /// The columns after `t_ms`, as written.
    pub names: Vec<String>,
    /// Each row's time, ms, strictly increasing.
    pub times_ms: Vec<f64>,
    /// Each row's values, one per name.
    pub rows: Vec<Vec<f64>>,
}

/// Why a CSV is not a recording.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RecordingError {
    /// Not readable as CSV (unbalanced quotes, a row of the wrong width…).
    #[error("line {line}: {message}")]
    Csv {
        /// 1-based line.
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// The header does not start with `t_ms`.
    #[error("the first column must be t_ms (the layout `servo-studio trajectory` writes); it is {0:?}")]
    NoTime(String),
    /// Nothing but `t_ms`.
    #[error("there is no column after t_ms: nothing moves")]
    NoColumns,
    /// A name given twice.
    #[error("column {0:?} is given twice")]
    Twice(String),
    /// No row.
    #[error("the recording has no rows: nothing to fit")]
    Empty,
    /// A field that is not a finite number.
    #[error("line {line}, column {column:?}: {text:?} is not a number")]
    NotNumber {
        /// 1-based line.
        line: u64,
        /// The column's name.
        column: String,
        /// The field.
        text: String,
    },
    /// Time going backwards or standing still.
    #[error("line {line}: t_ms {t_ms} does not come after {before} (rows must be in time order)")]
    NotIncreasing {
        /// 1-based line.
        line: u64,
        /// This row's time.
        t_ms: f64,
        /// The row before's.
        before: f64,
    },
    /// Over [`MAX_SECONDS`] or [`MAX_VALUES`].
    #[error("the recording is too large ({what}); at most {MAX_SECONDS} s and {MAX_VALUES} values are read")]
    TooLarge {
        /// How large.
        what: String,
    },
}

impl Recording {
    /// Reads a recording from CSV text.
    pub fn parse(text: &str) -> Result<Self, RecordingError> {
        let mut reader = csv::ReaderBuilder::new().has_headers(false).trim(csv::Trim::All).from_reader(text.as_bytes());
        let mut records = reader.records();
        let csv_error = |error: csv::Error| RecordingError::Csv {
            line: error.position().map_or(0, csv::Position::line),
            message: error.to_string(),
        };
        let header = match records.next() {
            Some(record) => record.map_err(csv_error)?,
            None => return Err(RecordingError::Empty),
        };
        let first = header.get(0).unwrap_or_default();
        if first != "t_ms" {
            return Err(RecordingError::NoTime(first.to_string()));
        }
        let names: Vec<String> = header.iter().skip(1).map(str::to_string).collect();
        if names.is_empty() {
            return Err(RecordingError::NoColumns);
        }
        for (index, name) in names.iter().enumerate() {
            if names[..index].contains(name) {
                return Err(RecordingError::Twice(name.clone()));
            }
        }
        let mut times_ms: Vec<f64> = Vec::new();
        let mut rows = Vec::new();
        for record in records {
            let record = record.map_err(csv_error)?;
            let line = record.position().map_or(0, csv::Position::line);
            let number = |column: usize| {
                let text = record.get(column).unwrap_or_default();
                text.parse::<f64>().ok().filter(|value| value.is_finite()).ok_or_else(|| RecordingError::NotNumber {
                    line,
                    column: if column == 0 { "t_ms".into() } else { names[column - 1].clone() },
                    text: text.to_string(),
                })
            };
            let t_ms = number(0)?;
            if let Some(&before) = times_ms.last()
                && t_ms <= before
            {
                return Err(RecordingError::NotIncreasing { line, t_ms, before });
            }
            if t_ms - times_ms.first().copied().unwrap_or(t_ms) > MAX_SECONDS * 1000.0 {
                return Err(RecordingError::TooLarge { what: format!("line {line} is past {MAX_SECONDS} s") });
            }
            if (rows.len() + 1).saturating_mul(names.len()) > MAX_VALUES {
                return Err(RecordingError::TooLarge {
                    what: format!("{} rows × {} columns", rows.len() + 1, names.len()),
                });
            }
            let row = (1..=names.len()).map(number).collect::<Result<Vec<f64>, _>>()?;
            times_ms.push(t_ms);
            rows.push(row);
        }
        if rows.is_empty() {
            return Err(RecordingError::Empty);
        }
        Ok(Self { names, times_ms, rows })
    }

    /// How long it lasts, ms.
    pub fn duration_ms(&self) -> f64 {
        self.times_ms.last().copied().unwrap_or(0.0) - self.times_ms.first().copied().unwrap_or(0.0)
    }

    /// The values every `update_ms` from the first row on (the first row
    /// included), each channel joined linearly between samples; as many
    /// updates as fit in the recording (a recording already at that rate is
    /// given back as it is).
    pub fn resample(&self, update_ms: f64) -> Vec<Vec<f64>> {
        if self.rows.len() < 2 {
            return self.rows.clone();
        }
        let start = self.times_ms.first().copied().unwrap_or(0.0);
        // At most an hour of updates (MAX_SECONDS): small and non-negative.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let count = (self.duration_ms() / update_ms + 1e-6).floor() as usize + 1;
        let mut out = Vec::with_capacity(count);
        let mut segment = 0;
        for index in 0..count {
            // Counts well below 2^52: exact.
            #[allow(clippy::cast_precision_loss)]
            let t_ms = start + index as f64 * update_ms;
            while segment + 2 < self.times_ms.len() && self.times_ms[segment + 1] < t_ms {
                segment += 1;
            }
            let (t0, t1) = (self.times_ms[segment], self.times_ms[segment + 1]);
            let along = ((t_ms - t0) / (t1 - t0)).clamp(0.0, 1.0);
            let (a, b) = (&self.rows[segment], &self.rows[segment + 1]);
            out.push(a.iter().zip(b).map(|(a, b)| if along >= 1.0 { *b } else { a + (b - a) * along }).collect());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_what_trajectory_writes_and_quoted_names() {
        let text = "t_ms,1 arm,\"2 hand, left\"\n0,10.00,-5.50\n10,11.00,-5.00\n20,12.00,-4.50\n";
        let recording = Recording::parse(text).expect("a recording");
        assert_eq!(recording.names, vec!["1 arm".to_string(), "2 hand, left".to_string()]);
        assert_eq!(recording.times_ms, vec![0.0, 10.0, 20.0]);
        assert_eq!(recording.rows[2], vec![12.0, -4.5]);
        // At its own rate it comes back as it is.
        assert_eq!(recording.resample(10.0), recording.rows);
    }

    #[test]
    fn resamples_any_rate_at_the_boards() {
        // 25 ms samples of a line, read at 10 ms.
        let text = "t_ms,a\n0,0\n25,25\n50,50\n75,75\n";
        let rows = Recording::parse(text).expect("a recording").resample(10.0);
        let values: Vec<f64> = rows.iter().map(|row| row[0]).collect();
        assert_eq!(values, vec![0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0]);
    }

    #[test]
    fn says_what_is_wrong() {
        assert_eq!(Recording::parse("time,a\n0,1\n1,2\n"), Err(RecordingError::NoTime("time".into())));
        assert_eq!(Recording::parse("t_ms\n0\n1\n"), Err(RecordingError::NoColumns));
        assert_eq!(Recording::parse("t_ms,a,a\n0,1,1\n1,2,2\n"), Err(RecordingError::Twice("a".into())));
        assert_eq!(Recording::parse("t_ms,a\n"), Err(RecordingError::Empty));
        assert_eq!(Recording::parse("t_ms,a\n0,1\n").map(|one| one.resample(10.0)), Ok(vec![vec![1.0]]));
        assert!(matches!(
            Recording::parse("t_ms,a\n0,1\n10,x\n"),
            Err(RecordingError::NotNumber { line: 3, ref column, ref text }) if column == "a" && text == "x"
        ));
        assert!(matches!(Recording::parse("t_ms,a\n0,1\n10,NaN\n"), Err(RecordingError::NotNumber { .. })));
        assert!(matches!(Recording::parse("t_ms,a\n10,1\n10,2\n"), Err(RecordingError::NotIncreasing { line: 3, .. })));
        assert!(matches!(Recording::parse("t_ms,a\n0,1\n10\n"), Err(RecordingError::Csv { line: 3, .. })));
        assert!(matches!(Recording::parse("t_ms,a\n0,1\n1e12,2\n"), Err(RecordingError::TooLarge { .. })));
    }
}

/// How long a recording counts in before it samples, s.
pub const COUNT_IN_S: f64 = 3.0;

/// Where a recording is at a moment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// Counting in: this many seconds before sampling starts.
    CountIn(f64),
    /// Sampling for this many seconds.
    Recording(f64),
}

/// A live movement being recorded: after a count-in, every sample given
/// (with its time, on the window's clock) is kept; [`Recorder::finish`]
/// gives the recording, to resample at the board's update and fit.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Recorder {
    /// When the first sample came (the count-in starts then), s.
    began_s: Option<f64>,
    /// Sampled (time since the count-in ended, ms; values).
    samples: Vec<(f64, Vec<f64>)>,
}

impl Recorder {
    /// A recorder that starts counting in at its first sample.
    pub fn new() -> Self {
        Self::default()
    }

    /// Where the recording is at `now_s`.
    pub fn phase(&self, now_s: f64) -> Phase {
        let since = now_s - self.began_s.unwrap_or(now_s);
        if since < COUNT_IN_S { Phase::CountIn(COUNT_IN_S - since) } else { Phase::Recording(since - COUNT_IN_S) }
    }

    /// Takes the values at `now_s` (kept once the count-in is over; a sample
    /// at the same time as the last replaces it).
    pub fn sample(&mut self, now_s: f64, values: &[f64]) {
        let began = *self.began_s.get_or_insert(now_s);
        let t_ms = (now_s - began - COUNT_IN_S) * 1000.0;
        if t_ms < 0.0 {
            return;
        }
        match self.samples.last_mut() {
            Some((last, kept)) if t_ms <= *last => kept.clone_from(&values.to_vec()),
            _ => self.samples.push((t_ms, values.to_vec())),
        }
    }

    /// The recording, with `names` for its columns; `None` when nothing was sampled.
    pub fn finish(self, names: Vec<String>) -> Option<Recording> {
        if self.samples.is_empty() {
            return None;
        }
        let (times_ms, rows) = self.samples.into_iter().unzip();
        Some(Recording { names, times_ms, rows })
    }
}

#[cfg(test)]
mod recorder_tests {
    use super::*;

    #[test]
    fn counts_in_then_keeps_what_it_is_given_in_time_order() {
        let mut recorder = Recorder::new();
        recorder.sample(10.0, &[1.0]);
        assert_eq!(recorder.phase(11.0), Phase::CountIn(2.0));
        recorder.sample(12.5, &[2.0]);
        recorder.sample(13.0, &[3.0]);
        recorder.sample(13.0, &[4.0]);
        recorder.sample(13.5, &[5.0]);
        assert_eq!(recorder.phase(14.0), Phase::Recording(1.0));
        let recording = recorder.finish(vec!["a".into()]).expect("sampled");
        assert_eq!(recording.times_ms, vec![0.0, 500.0]);
        assert_eq!(recording.rows, vec![vec![4.0], vec![5.0]]);
        assert_eq!(Recorder::new().finish(vec![]), None);
    }
}
