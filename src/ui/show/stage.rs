//! The show's stage: every device's figure in one 3D view, placed on the
//! floor where the user puts it (metres and a heading per device), posed at
//! the scrub's time as the boards would have it (`show::at`): a PLEN2 by the
//! firmware's playback, a rigged servo board by its macro's trace (a board
//! with no rig as a small box), a base as a body with a nose toward its
//! heading where its drives have taken it.

use crate::figure::{self, Mat3, Placed, Shape, Vec3, WorldSolid};
use crate::show::at::{Posed, hold};
use crate::show::passes::Axis;
use crate::show::{Device, Show};
use crate::ui::view3d::{Scene, View};

use super::{ShowAction, ShowWords};

/// The stage's view and where the scrub is.
#[derive(Debug, Default)]
pub struct Stage {
    /// The show's time shown, ms.
    pub scrub_ms: u64,
    /// The show's span as the lanes last showed it, ms (where a preview ends).
    pub span_ms: u64,
    /// An axis being recorded: the device's name, the axis and its value now
    /// (degrees), shown on the figure instead of what the show has there.
    pub held: Option<(String, Axis, f64)>,
    view: View,
    plen2: Option<figure::Chain>,
    /// Previewing: when it began and the time shown then.
    preview: Option<(std::time::Instant, u64)>,
    /// What each device does over time, worked out once for the show as it stands.
    pub timeline: crate::show::timeline::Timeline,
    /// The show's sound for the preview (its own worker: a stalled sound server waits there, not here).
    sound: Option<crate::ui::sound::SoundOut>,
}

/// mm in a metre (the figures are in mm).
const MM: f32 = 1000.0;

impl Stage {
    /// The scrub, each device's place, and the 3D view of them all.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        (show, span_ms): (&mut Show, u64),
        editable: bool,
        words: &ShowWords,
        actions: &mut Vec<crate::ui::Action>,
    ) {
        ui.horizontal(|ui| {
            let label = ui.label(words.scrub);
            // Whole ms of a show: exact in f64.
            #[allow(clippy::cast_precision_loss)]
            let mut seconds = self.scrub_ms as f64 / 1000.0;
            #[allow(clippy::cast_precision_loss)]
            let end = span_ms as f64 / 1000.0;
            ui.spacing_mut().slider_width = (ui.available_width() - 120.0).clamp(200.0, 700.0);
            let slider = egui::Slider::new(&mut seconds, 0.0..=end).suffix(" s").fixed_decimals(2);
            let running = self.preview.is_some();
            let (caption, action) = if running {
                (words.stop_preview, ShowAction::Preview(false))
            } else {
                (words.preview, ShowAction::Preview(true))
            };
            if ui.button(caption).clicked() {
                actions.push(crate::ui::Action::Show(action));
            }
            if ui.add(slider).labelled_by(label.id).changed() {
                // Within the show's span: whole ms.
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let ms = (seconds * 1000.0).round().max(0.0) as u64;
                self.scrub_ms = ms;
            }
        });
        ui.horizontal_top(|ui| {
            ui.vertical(|ui| places_ui(ui, show, editable, words));
            let size = egui::vec2(ui.available_width().max(200.0), 240.0);
            let (rect, _) = ui.allocate_exact_size(size, egui::Sense::hover());
            let scene = self.scene(show);
            self.view.show(ui, rect, &scene, words.stage);
        });
    }

    /// Whether the stage plays the show on its own (the scrub running with the clock).
    pub fn previewing(&self) -> bool {
        self.preview.is_some()
    }

    /// Plays the show on the stage from the time shown, with its sound
    /// (`sound`: its file and where it starts on the show's time, ms).
    pub fn start_preview(&mut self, sound: Option<(std::path::PathBuf, i64)>, waker: &crate::link::Waker) {
        self.stop_preview();
        if let Some((file, offset_ms)) = sound {
            // Whole ms of a show: exact in f64.
            #[allow(clippy::cast_precision_loss)]
            let into_sound_s = (i128::from(self.scrub_ms) - i128::from(offset_ms)) as f64 / 1000.0;
            let out = self.sound.get_or_insert_with(|| crate::ui::sound::SoundOut::new(None, waker.clone()));
            if into_sound_s >= 0.0 {
                out.play(file, into_sound_s, None);
            }
        }
        self.preview = Some((std::time::Instant::now(), self.scrub_ms));
    }

    /// Stops a preview (and its sound) where it is.
    pub fn stop_preview(&mut self) {
        self.preview = None;
        if let Some(sound) = &mut self.sound {
            sound.silence();
        }
    }

    /// Moves a preview's scrub on with the clock, ending it at `span_ms`; whether it still runs.
    pub fn advance(&mut self, span_ms: u64) -> bool {
        if let Some(sound) = &mut self.sound {
            sound.poll(std::time::Instant::now());
        }
        let Some((began, from)) = self.preview else { return false };
        // Milliseconds of a show: far within u64.
        #[allow(clippy::cast_possible_truncation)]
        let now = from + began.elapsed().as_millis() as u64;
        self.scrub_ms = now.min(span_ms);
        if now >= span_ms {
            self.stop_preview();
        }
        self.preview.is_some()
    }

    /// Every device at the scrub's time, each at its place.
    pub fn scene(&mut self, show: &Show) -> Scene {
        let mut solids = Vec::new();
        for (index, device) in show.devices.iter().enumerate() {
            let Some(mut posed) = self.timeline.posed_at(show, index, self.scrub_ms) else { continue };
            if let Some((name, axis, value)) = &self.held
                && *name == device.name
            {
                hold(&mut posed, *axis, *value);
            }
            let base = placed(device.place.x_m, device.place.y_m, device.place.heading_deg);
            match posed {
                Posed::Joints(values) => {
                    let chain = self.plen2.get_or_insert_with(figure::plen2::chain);
                    let placed = chain.pose_from(base, &figure::plen2::angles(chain, &values));
                    solids.extend(chain.dress(&placed, false));
                }
                Posed::Servos(degrees) => solids.extend(servo_board(device, &degrees, base)),
                Posed::Base(place) => solids.extend(base_body(placed(place.x_m, place.y_m, place.heading_deg))),
            }
        }
        Scene { solids, ground_z: 0.0, ..Scene::default() }
    }
}

/// A place on the floor (m, degrees) as the figures' frame (mm, z up).
fn placed(x_m: f64, y_m: f64, heading_deg: f64) -> Placed {
    // Metres on a stage: well within f32.
    #[allow(clippy::cast_possible_truncation)]
    let (x, y, heading) = (x_m as f32, y_m as f32, heading_deg.to_radians() as f32);
    Placed { position: Vec3::new(x * MM, y * MM, 0.0), rotation: Mat3::from_rotation_z(heading) }
}

/// A servo board's rig posed at `degrees`, standing on the floor at `base`;
/// a board with no rig: a small box where it stands.
fn servo_board(device: &Device, degrees: &std::collections::BTreeMap<u8, f64>, base: Placed) -> Vec<WorldSolid> {
    let project = &device.project.servo;
    if project.servos.iter().all(|servo| servo.rig.is_none()) {
        return vec![solid(base, Vec3::new(0.0, 0.0, 20.0), Vec3::new(60.0, 40.0, 20.0), [90, 140, 90])];
    }
    let (chain, index_of) = figure::rig::chain(project);
    let homes = project.servos.iter().map(|s| (s.id, f64::from(s.home_deg))).collect();
    let home = chain.pose(&figure::rig::angles(project, &index_of, &homes, chain.links.len()));
    // Its feet (its lowest point at home) on the floor.
    let lowest = chain.dress(&home, false).iter().map(|s| s.at.z).fold(0.0_f32, f32::min);
    let lifted = Placed { position: base.position + Vec3::new(0.0, 0.0, -lowest), rotation: base.rotation };
    let placed = chain.pose_from(lifted, &figure::rig::angles(project, &index_of, degrees, chain.links.len()));
    chain.dress(&placed, false)
}

/// An rFLEX base: a round-ish body and a nose toward its heading.
fn base_body(at: Placed) -> Vec<WorldSolid> {
    vec![
        solid(at, Vec3::new(0.0, 0.0, 150.0), Vec3::new(250.0, 250.0, 150.0), [120, 120, 140]),
        solid(at, Vec3::new(250.0, 0.0, 250.0), Vec3::new(60.0, 60.0, 40.0), [220, 160, 60]),
    ]
}

/// A box of half-size `half` centred at `offset` in `at`'s frame.
fn solid(at: Placed, offset: Vec3, half: Vec3, color: [u8; 3]) -> WorldSolid {
    WorldSolid {
        at: at.position + at.rotation * offset,
        rotation: at.rotation,
        shape: Shape::Box { half },
        color,
        faint: false,
        link: 0,
    }
}

/// Each device's place on the floor: x and y (m), heading (°).
fn places_ui(ui: &mut egui::Ui, show: &mut Show, editable: bool, words: &ShowWords) {
    egui::Grid::new("show-places").show(ui, |ui| {
        for head in [words.device, "x", "y", words.heading] {
            ui.strong(head);
        }
        ui.end_row();
        for device in &mut show.devices {
            let name = ui.label(&device.name).id;
            let place = &mut device.place;
            for (value, suffix, range) in [
                (&mut place.x_m, " m", -50.0..=50.0),
                (&mut place.y_m, " m", -50.0..=50.0),
                (&mut place.heading_deg, "°", -360.0..=360.0),
            ] {
                let drag = egui::DragValue::new(value).speed(0.01).range(range).suffix(suffix).max_decimals(2);
                ui.add_enabled(editable, drag).labelled_by(name);
            }
            ui.end_row();
        }
    });
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::project::{Family, Project};
    use crate::show::{Cue, Place, Start};

    /// The stage draws each device at its place, posed at the scrub: a base
    /// driving along +x is farther along at 2 s than at 0, a PLEN2 stands
    /// where it was put.
    #[test]
    fn every_device_stands_at_its_place_posed_at_the_scrub() {
        let mut show = Show::of_one("plen", Project::empty(Family::Plen2));
        show.devices[0].place = Place { x_m: -1.0, y_m: 0.5, heading_deg: 0.0 };
        show.add_device("base", Project::empty(Family::Rflex));
        show.cues.push(Cue {
            device: "base".into(),
            at_ms: 0,
            start: Start::Drive { speed_m_s: 0.5, turn_deg_s: 0.0, for_ms: 10_000 },
        });
        let mut stage = Stage::default();
        let centre_x = |scene: &Scene, link_colour: [u8; 3]| {
            scene.solids.iter().find(|solid| solid.color == link_colour).map(|solid| solid.at.x).unwrap()
        };
        let at_zero = stage.scene(&show);
        stage.scrub_ms = 2000;
        let at_two = stage.scene(&show);
        let body = [120, 120, 140];
        let moved = centre_x(&at_two, body) - centre_x(&at_zero, body);
        assert!((moved - 1000.0).abs() < 1e-2, "0.5 m/s for 2 s is 1000 mm: {moved}");
        // The PLEN2's solids are all near its place (within its own size).
        let plen: Vec<&WorldSolid> =
            at_two.solids.iter().filter(|s| s.color != body && s.color != [220, 160, 60]).collect();
        assert!(!plen.is_empty());
        assert!(
            plen.iter().all(|s| (s.at.x + 1000.0).abs() < 200.0 && (s.at.y - 500.0).abs() < 200.0),
            "at (−1 m, 0.5 m)"
        );
    }
}
