//! Pololu Maestro Control Center's settings file (`<UscSettings>`): channels
//! (name, mode, min, max, home, speed, acceleration; positions in quarter
//! microseconds) and sequences of frames, each a duration in ms and a target
//! per channel (0 = the channel's pulses off).

use super::bounds;
use super::format::{Format, ReadError, number};
use super::source::{Body, Channel, Clip, Key, Source, Timing, Unit};
use super::xml::{self, Element};

/// Quarter-microseconds: 1500 µs at 0°, 10 µs a degree (docs/import-export.md).
pub const QUARTER_US: Unit = Unit { zero: 6000.0, per_degree: 40.0, label: "¼ µs" };

/// What a settings file may hold, counted as it is read.
const MOST: [xml::Most; 3] = [
    xml::Most {
        name: "Channel",
        count: bounds::MAX_CHANNELS,
        because: "a board has no more channels (is the file damaged?)",
    },
    xml::Most { name: "Frame", count: bounds::MAX_KEYS, because: bounds::TOO_MANY_KEYS },
    xml::Most { name: "Sequence", count: bounds::MAX_KEYS, because: bounds::TOO_MANY_KEYS },
];

/// Reads a settings file.
pub fn read(text: &str) -> Result<Source, ReadError> {
    let root = xml::parse_within(text, &MOST)?;
    if root.name != "UscSettings" {
        return Err(ReadError::at(
            root.line,
            &root.name,
            "the root element is not <UscSettings>: is this a Maestro settings file?",
        ));
    }
    let channels_element = root.child("Channels").ok_or_else(|| {
        ReadError::at(root.line, "UscSettings", "no <Channels>: the file is cut short or not a settings file")
    })?;
    let mut source = Source {
        format: Format::Maestro,
        channels: Vec::new(),
        clips: Vec::new(),
        dropped: Vec::new(),
        notes: Vec::new(),
    };
    // Position in the file → index into `source.channels` (None: not a servo).
    let mut servos: Vec<Option<usize>> = Vec::new();
    for (index, element) in channels_element.children_named("Channel").enumerate() {
        let mode = element.attr("mode").unwrap_or("Servo");
        if !mode.starts_with("Servo") {
            servos.push(None);
            source.drop_note(format!("channel {index} ({mode}): not a servo"));
            continue;
        }
        servos.push(Some(source.channels.len()));
        let (channel, accelerates) = channel(index, element)?;
        if accelerates {
            source.drop_note("acceleration limits (the board moves each step at one speed)");
        }
        source.channels.push(channel);
    }
    if servos.is_empty() {
        return Err(ReadError::at(channels_element.line, "Channels", "no <Channel> in it"));
    }
    if root.child("Script").is_some_and(|script| !script.text.trim().is_empty()) {
        source.drop_note("the script (a board runs no Maestro script)");
    }
    if let Some(sequences) = root.child("Sequences") {
        for sequence in sequences.children_named("Sequence") {
            let mut dropped = Vec::new();
            let clip = sequence_clip(sequence, &servos, source.channels.len(), &mut dropped)?;
            source.clips.push(clip);
            dropped.into_iter().for_each(|note| source.drop_note(note));
        }
    }
    Ok(source)
}

fn attr_number(element: &Element, name: &str) -> Result<Option<f64>, ReadError> {
    element.attr(name).map(|text| number(text, element.line, &element.name, name)).transpose()
}

fn channel(index: usize, element: &Element) -> Result<(Channel, bool), ReadError> {
    let mut channel = Channel::new(index.to_string(), QUARTER_US);
    channel.name = element.attr("name").unwrap_or_default().trim().to_string();
    let (min, max) = (attr_number(element, "min")?, attr_number(element, "max")?);
    if let (Some(min), Some(max)) = (min, max) {
        if min > max {
            return Err(ReadError::at(element.line, "Channel", format!("min {min} is above max {max}")));
        }
        channel.limits = Some((min, max));
    }
    let goes_home = element.attr("homemode").is_some_and(|mode| mode.eq_ignore_ascii_case("Goto"));
    channel.home = if goes_home { attr_number(element, "home")? } else { None };
    channel.speed = attr_number(element, "speed")?;
    let accelerates = attr_number(element, "acceleration")?.is_some_and(|acceleration| acceleration > 0.0);
    Ok((channel, accelerates))
}

fn sequence_clip(
    sequence: &Element,
    servos: &[Option<usize>],
    channel_count: usize,
    dropped: &mut Vec<String>,
) -> Result<Clip, ReadError> {
    let mut keys = Vec::new();
    for frame in sequence.children_named("Frame") {
        let duration =
            attr_number(frame, "duration")?.ok_or_else(|| ReadError::at(frame.line, "Frame", "no duration"))?;
        if duration < 0.0 {
            return Err(ReadError::at(frame.line, "Frame", format!("duration {duration} is negative")));
        }
        let mut values = vec![None; channel_count];
        let mut words = frame.text.split_whitespace();
        for (position, word) in words.by_ref().enumerate() {
            if word == "s" || word == "a" {
                dropped.push("per-frame speeds and accelerations (the channels' speed limits are used)".into());
                break;
            }
            let target = number(word, frame.line, "Frame", "target")?;
            let Some(slot) = servos.get(position) else {
                return Err(ReadError::at(
                    frame.line,
                    "Frame",
                    format!(
                        "{} targets, and the file has {} channels",
                        frame.text.split_whitespace().take_while(|w| *w != "s").count(),
                        servos.len()
                    ),
                ));
            };
            if target == 0.0 {
                dropped.push("a target of 0 (a channel's pulses off): the servo stays where it is".into());
                continue;
            }
            if let Some(index) = slot {
                values[*index] = Some(target);
            }
        }
        let name = frame.attr("name").unwrap_or_default().to_string();
        keys.push(Key { values, timing: Timing::Frame { duration_ms: duration }, name });
    }
    Ok(Clip::new(sequence.attr("name").unwrap_or("sequence"), Body::Keys(keys)))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    const FILE: &str = r#"<!--Pololu Maestro servo controller settings file, http://www.pololu.com/catalog/product/1350-->
<UscSettings version="1">
  <NeverSuspend>false</NeverSuspend>
  <Channels ServosAvailable="6" ServoPeriod="156">
    <!--Channel 0-->
    <Channel name="jaw" mode="Servo" min="3968" max="8000" homemode="Goto" home="6000" speed="20" acceleration="0" neutral="6000" range="1905" />
    <Channel name="" mode="Output" min="3968" max="8000" homemode="Off" home="3968" speed="0" acceleration="0" neutral="6000" range="1905" />
    <Channel name="neck &amp; head" mode="Servo" min="4000" max="8000" homemode="Off" home="4000" speed="0" acceleration="0" neutral="6000" range="1905" />
  </Channels>
  <Sequences>
    <Sequence name="nod">
      <Frame name="Frame 0" duration="500">6400 0 5600</Frame>
      <Frame name="Frame 1" duration="250">6000 0 6000</Frame>
    </Sequence>
  </Sequences>
  <Script ScriptDone="true">begin 1 end</Script>
</UscSettings>"#;

    #[test]
    fn channels_sequences_and_frames_are_read_as_the_file_says() {
        let source = read(FILE).unwrap();
        let keys: Vec<&str> = source.channels.iter().map(|channel| channel.key.as_str()).collect();
        assert_eq!(keys, ["0", "2"], "the Output channel is not a servo");
        assert_eq!(source.channels[1].name, "neck & head");
        assert_eq!(source.channels[0].home, Some(6000.0));
        assert_eq!(source.channels[1].home, None, "homemode Off: no home");
        assert_eq!(source.channels[0].speed, Some(20.0));
        let Body::Keys(keys) = &source.clips[0].body else { panic!() };
        assert_eq!(keys[0].values, [Some(6400.0), Some(5600.0)]);
        assert_eq!(keys[1].timing, Timing::Frame { duration_ms: 250.0 });
        assert!(source.dropped.iter().any(|note| note.contains("script")));
    }

    #[test]
    fn bad_files_say_where() {
        let wrong_root = read("<Settings>\n</Settings>").unwrap_err();
        assert!(wrong_root.to_string().contains("not <UscSettings>"), "{wrong_root}");
        let word = read(&FILE.replace("6400 0 5600", "6400 x 5600")).unwrap_err();
        assert_eq!(word.line, Some(12), "{word}");
        assert!(word.to_string().contains("target \"x\" is not a number"), "{word}");
        let cut = read(&FILE[..FILE.find("</Sequence>").unwrap()]).unwrap_err();
        assert!(cut.to_string().contains("never closed"), "{cut}");
    }
}
