//! Damaged files, to every reader of the newer inputs: the kept sound
//! fixtures (real FLAC, MP3 and Ogg Vorbis encoders' output, and a WAV),
//! a mesh in each format, and a file of each other tool — cut short, with
//! bytes overwritten, or with bytes put in. Whatever the damage, each reader
//! answers (the file read, or an error naming it): none panics, none hangs.

#![allow(clippy::unwrap_used, clippy::cast_possible_truncation)]

use proptest::prelude::*;

use servo_studio::interchange::{self, Format};

/// One kind of damage.
#[derive(Clone, Debug)]
enum Damage {
    /// Cut at this share of the file.
    Cut(f64),
    /// These bytes overwritten (share of the file, new byte).
    Overwrite(Vec<(f64, u8)>),
    /// These bytes put in (share of the file, byte).
    Insert(Vec<(f64, u8)>),
}

fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        (0.0..1.0f64).prop_map(Damage::Cut),
        prop::collection::vec((0.0..1.0f64, any::<u8>()), 1..24).prop_map(Damage::Overwrite),
        prop::collection::vec((0.0..1.0f64, any::<u8>()), 1..24).prop_map(Damage::Insert),
    ]
}

fn damaged(original: &[u8], damage: &Damage) -> Vec<u8> {
    let at = |share: f64, len: usize| ((share * len as f64) as usize).min(len.saturating_sub(1));
    let mut bytes = original.to_vec();
    match damage {
        Damage::Cut(share) => bytes.truncate(at(*share, original.len())),
        Damage::Overwrite(changes) => {
            for (share, byte) in changes {
                let index = at(*share, bytes.len());
                bytes[index] = *byte;
            }
        }
        Damage::Insert(changes) => {
            for (share, byte) in changes {
                let index = at(*share, bytes.len());
                bytes.insert(index, *byte);
            }
        }
    }
    bytes
}

fn fixture(name: &str) -> Vec<u8> {
    std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sound").join(name)).unwrap()
}

/// A binary STL of one triangle and an OBJ of one face.
fn meshes() -> [(&'static str, Vec<u8>); 2] {
    let mut stl = vec![0u8; 80];
    stl.extend(1u32.to_le_bytes());
    for value in [0.0f32, 0.0, 1.0, 0.0, 0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 10.0, 0.0] {
        stl.extend(value.to_le_bytes());
    }
    stl.extend([0, 0]);
    let obj = b"v 0 0 0\nv 10 0 0\nv 0 10 0\nvn 0 0 1\nf 1//1 2//1 3//1\n".to_vec();
    [("part.stl", stl), ("part.obj", obj)]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn a_damaged_sound_is_read_or_named_never_a_panic(damage in damage(), which in 0..4usize) {
        let (name, original) = match which {
            0 => ("clicks.wav", servo_studio::audio::pcm16_wav(&[0.5; 4000], 8_000, 2)),
            1 => ("clicks.flac", fixture("clicks.flac")),
            2 => ("clicks.mp3", fixture("clicks.mp3")),
            _ => ("clicks.ogg", fixture("clicks.ogg")),
        };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::write(&path, damaged(&original, &damage)).unwrap();
        if let Err(error) = servo_studio::audio::analyse(&path, 0.5, |_| {}) {
            prop_assert!(error.to_string().contains(name), "{error}");
        }
    }

    #[test]
    fn a_damaged_mesh_is_read_or_named_never_a_panic(damage in damage(), which in 0..2usize) {
        let (name, original) = meshes()[which].clone();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::write(&path, damaged(&original, &damage)).unwrap();
        if let Err(error) = servo_studio::figure::mesh::Mesh::load(&path) {
            prop_assert!(error.to_string().contains(name), "{error}");
        }
    }

    #[test]
    fn a_damaged_file_of_another_tool_is_read_or_named_never_a_panic(damage in damage(), which in 0..4usize) {
        let (format, original) = match which {
            0 => (Format::Maestro, super::maestro::SETTINGS.to_string()),
            1 => (Format::Mtn, super::robotis::mtn("1.0")),
            2 => (Format::Mtnx, super::robotis::MTNX.to_string()),
            _ => (Format::Blender, r#"{"fps": 24, "frames": 3, "servos": {"1": {"name": "jaw", "positions": [375, 400, 420]}}}"#.to_string()),
        };
        let bytes = damaged(original.as_bytes(), &damage);
        let text = String::from_utf8_lossy(&bytes);
        if let Ok(source) = interchange::read(format, &text) {
            // What reads is also converted, or refused with a reason.
            for family in [servo_studio::project::Family::Servo, servo_studio::project::Family::Plen2] {
                let map = interchange::JointMap::for_source(&source, family, None);
                let _ = interchange::build::build(&source, &map, &interchange::build::Options::new(family));
            }
        }
    }
}
