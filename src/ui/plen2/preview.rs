//! The PLEN2's 3D preview: beside the joints, the live pose; beside the
//! motion editor, the motion as the firmware plays it (plen2.md §6) at the
//! time cursor, with a faint ghost of the frame it is moving to. What a
//! joint shows is home + value clamped to the joint settings, minus home: what
//! the servo really does.

use crate::authoring::bake;
use crate::device::plen2::playback::{self, DEVICE_IDS, Playback, Settings, StoredMotions};
use crate::figure::ik::Limb;
use crate::figure::{self, Chain, Placed};
use crate::project::plen2::{Joint, Plen2Project};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;
use crate::ui::plen2::action::Plen2Action;
use crate::ui::plen2::captions::Plen2Words;
use crate::ui::transport::Transport;
use crate::ui::view3d::posing::{Posing, Rig};
use crate::ui::view3d::{Handle, Scene, Touch, View};

/// Each limb's twin: the feet, then the hands (as `figure::plen2::limbs` lists them).
const TWINS: [Option<usize>; 4] = [Some(1), Some(0), Some(3), Some(2)];

/// At most this long is played out for the preview (a loop forever stops here).
const MAX_CYCLES: usize = 916;

/// What a playback was computed for: document revision, slot, slot played before.
type PlaybackKey = (u64, u8, Option<u8>);

/// The preview's state.
#[derive(Debug)]
pub struct Preview {
    chain: Chain,
    joints_view: View,
    motion_view: View,
    /// The motion editor's time cursor.
    pub transport: Transport,
    /// The sound lane under it.
    pub lane: crate::ui::sound::SoundLane,
    /// The motion played before the previewed one (none: power-up).
    pub after: Option<u8>,
    /// The playback, for (document revision, slot, played after).
    playback: Option<(PlaybackKey, Playback, Settings)>,
    /// The frame selected in the editor when last drawn (slot, index).
    selected: Option<(u8, usize)>,
    /// What the view showed last: each device's value relative to home, clamped.
    pub shown: Option<[i16; DEVICE_IDS]>,
    /// The turn last sent for the joint a drag in the live view holds (tenths).
    turned: Option<i32>,
    /// What the live view drew last.
    live_scene: Scene,
    /// The hands and feet the live figure is posed by.
    limbs: Vec<Limb>,
    /// How they are posed.
    pub posing: Posing,
}

impl Default for Preview {
    fn default() -> Self {
        let chain = figure::plen2::chain();
        Self {
            limbs: figure::plen2::limbs(&chain),
            posing: Posing::default(),
            chain,
            joints_view: View::default(),
            motion_view: View::default(),
            transport: Transport::default(),
            lane: crate::ui::sound::SoundLane::default(),
            after: None,
            playback: None,
            selected: None,
            shown: None,
            turned: None,
            live_scene: Scene::default(),
        }
    }
}

impl Preview {
    /// The figure for `values` (and a ghost for `ghost`), both relative to home and clamped.
    fn scene(&self, values: &[i16; DEVICE_IDS], ghost: Option<&[i16; DEVICE_IDS]>, base: Placed) -> Scene {
        let mut solids = Vec::new();
        if let Some(ghost) = ghost {
            let placed = self.chain.pose_from(base, &figure::plen2::angles(&self.chain, ghost));
            solids.extend(self.chain.dress(&placed, true));
        }
        let placed = self.chain.pose_from(base, &figure::plen2::angles(&self.chain, values));
        solids.extend(self.chain.dress(&placed, false));
        Scene { solids, ground_z: 0.0, ..Scene::default() }
    }

    /// The joint a link of the figure is.
    fn joint_of(&self, link: usize) -> Option<Joint> {
        let name = &self.chain.links.get(link)?.name;
        Joint::ALL.into_iter().find(|joint| joint.name() == name)
    }

    /// The live pose beside the joint sliders (`pose`: absolute angles,
    /// device-map order), to be posed by touching it: hovering a joint's link
    /// names it and its angle, a click selects it, a drag turns it.
    pub fn joints(
        &mut self,
        ui: &mut egui::Ui,
        (project, pose): (&Plen2Project, &[i16; 18]),
        selected: Option<Joint>,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let settings = playback::joint_settings(project);
        let mut values = [0; DEVICE_IDS];
        for joint in Joint::ALL {
            let device = usize::from(joint.device_id());
            values[device] = pose[joint.index()] - settings[device].0;
        }
        let values = playback::clamped(&values, &settings);
        self.shown = Some(values);
        let angles = figure::plen2::angles(&self.chain, &values);
        let limits = figure::plen2::limits(&self.chain, &settings);
        let rig = Rig {
            chain: &self.chain,
            limbs: &self.limbs,
            twins: &TWINS,
            limits: &limits,
            mm_per_unit: figure::plen2::MM_PER_UNIT,
        };
        self.posing.toolbar(ui, &self.limbs, &mut self.joints_view, words.lang);
        let base = self.posing.base(&rig, &angles);
        let mut scene = self.scene(&values, None, base);
        let placed = self.chain.pose_from(base, &angles);
        scene.ends = self.posing.ends(&rig, &placed, words.lang);
        scene.gap = self.posing.gap();
        scene.handles = (0..self.chain.links.len())
            .map(|link| {
                let joint = self.joint_of(link)?;
                let angle = f64::from(pose[joint.index()]) / 10.0;
                let reading = format!("{} #{}  {angle:.1}°", joint.name(), joint.device_id());
                Some(Handle { reading, joint: self.chain.joint(&placed, link) })
            })
            .collect();
        scene.selected = selected.and_then(|joint| self.chain.link(joint.name()));
        let rect = ui.available_rect_before_wrap();
        let (response, touch) = self.joints_view.show(ui, rect, &scene, words.robot_preview);
        if touch.hovered.is_none() && touch.hovered_end.is_none() {
            response.on_hover_text(words.preview_hint);
        }
        let posed = self.posing.reach(&rig, &angles, base, &touch, words.lang);
        if let Some(solved) = posed.angles {
            let values = figure::plen2::values(&self.chain, &solved);
            let pose: [i16; 18] = std::array::from_fn(|index| {
                let device = usize::from(Joint::ALL[index].device_id());
                settings[device].0.saturating_add(values[device])
            });
            actions.push(Action::family(Plen2Action::Pose(pose)));
        }
        if posed.done {
            actions.push(Action::family(Plen2Action::TurnDone));
        }
        self.live_scene = scene;
        self.touched(touch, actions);
    }

    /// Where on the screen an end (a limb's, by `figure::plen2::limbs`'
    /// order; then the pelvis) was last drawn in the live view.
    pub fn end_on_screen(&self, end: usize) -> Option<egui::Pos2> {
        self.joints_view.on_screen(self.live_scene.ends.get(end)?.at)
    }

    /// What touching the live figure asks for.
    fn touched(&mut self, touch: Touch, actions: &mut Vec<Action>) {
        if let Some(joint) = touch.clicked.and_then(|link| self.joint_of(link)) {
            actions.push(Action::family(Plen2Action::SelectJoint(Some(joint))));
        }
        // A joint's value turns its link by as many tenths of a degree, right-hand rule.
        if let Some((link, by_tenths)) = touch.new_turn(&mut self.turned, 10.0)
            && let Some(joint) = self.joint_of(link)
        {
            actions.push(Action::family(Plen2Action::TurnJoint { joint, by_tenths }));
        }
        if touch.let_go.is_some() {
            actions.push(Action::family(Plen2Action::TurnDone));
        }
    }

    #[cfg(any(test, feature = "test-api"))]
    /// The live view's camera, as last drawn.
    pub fn joints_camera(&self) -> Option<crate::ui::view3d::Camera> {
        self.joints_view.drawn().map(|(camera, _)| camera)
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Where on the screen a point of `joint`'s link was last drawn in the
    /// live view (the one farthest from its axis), to touch it there.
    pub fn joint_on_screen(&self, joint: Joint) -> Option<egui::Pos2> {
        let grip = crate::ui::view3d::grip(&self.live_scene, self.chain.link(joint.name())?)?;
        self.joints_view.on_screen(grip)
    }

    /// Plays `slot` out again when the revision, the slot or what it is played after changed.
    fn refresh(&mut self, project: &Plen2Project, revision: u64, slot: u8) {
        let key = (revision, slot, self.after);
        if self.playback.as_ref().is_none_or(|(at, _, _)| *at != key) {
            let stored = StoredMotions::new(project);
            let from = self.after.map_or([0; DEVICE_IDS], |previous| playback::after(&stored, previous, MAX_CYCLES));
            let played = playback::play(&stored, slot, from, MAX_CYCLES);
            self.playback = Some((key, played, playback::joint_settings(project)));
        }
    }

    /// The motion in `slot` as the robot plays it: the time cursor, the view,
    /// and where it starts from. `frame` is the frame selected in the editor
    /// (the cursor goes to where it is reached when it changes); `pose` is the
    /// joint sliders' (absolute).
    pub fn motion(
        &mut self,
        ui: &mut egui::Ui,
        (project, revision): (&Plen2Project, u64),
        (slot, frame): (u8, usize),
        pose: &[i16; 18],
        (view, actions): (&crate::ui::shell::ShellView<'_>, &mut Vec<Action>),
    ) {
        let words = view.language.strings();
        let now = ui.input(|input| input.time);
        ui.horizontal(|ui| self.played_after_ui(ui, project, words));
        self.refresh(project, revision, slot);
        let Some((_, played, settings)) = &self.playback else { return };
        if self.selected != Some((slot, frame)) {
            self.selected = Some((slot, frame));
            // The cursor to where the selected frame is reached (its last cycle):
            // a frame with a curve is stored as several, the last of them.
            let stored =
                project.motions.iter().find(|m| m.slot == slot).filter(|m| bake::has_curves(m)).and_then(|m| {
                    bake::bake_plen2(m, bake::DEFAULT_TOLERANCE_TENTHS)
                        .source
                        .iter()
                        .rposition(|&source| source == frame)
                });
            let index = u8::try_from(stored.unwrap_or(frame)).unwrap_or(0);
            if let Some(first) = played.first_cycle_of(slot, index) {
                let last = played.frames[first..].iter().take_while(|f| **f == (slot, index)).count() + first - 1;
                // Cycle counts are small.
                #[allow(clippy::cast_precision_loss)]
                let t = (last as f64 + 0.5) * Playback::CYCLE_MS;
                self.transport.seek(t, now);
            }
        }
        let marks: Vec<f64> = (0..played.frames.len())
            .filter(|&cycle| cycle == 0 || played.frames[cycle] != played.frames[cycle - 1])
            // Cycle counts are small.
            .map(|cycle| {
                #[allow(clippy::cast_precision_loss)]
                let t = cycle as f64 * Playback::CYCLE_MS;
                t
            })
            .collect();
        self.transport.ui(ui, view.sound.span_ms(played.duration_ms()), &marks, words);
        self.lane.ui(ui, view.sound, (&mut self.transport, played.duration_ms(), &marks), view.language, actions);
        warnings(ui, (project, slot), played, (settings, pose), words);
        let Some(cycle) = played.cycle_at(self.transport.t_ms) else {
            self.shown = None;
            return;
        };
        let values = playback::clamped(&played.cycles[cycle], settings);
        let (target_slot, target_index) = played.frames[cycle];
        let ghost = project
            .motions
            .iter()
            .find(|m| m.slot == target_slot)
            .and_then(|m| m.frames.get(usize::from(target_index)))
            .map(|target| {
                let mut out = [0; DEVICE_IDS];
                for joint in Joint::ALL {
                    out[usize::from(joint.device_id())] = target.values_tenths_deg.get(joint);
                }
                playback::clamped(&out, settings)
            });
        self.shown = Some(values);
        let scene = self.scene(&values, ghost.as_ref(), Placed::ORIGIN);
        let rect = ui.available_rect_before_wrap();
        self.motion_view.show(ui, rect, &scene, words.robot_preview).0.on_hover_text(words.preview_hint);
    }

    /// Which motion the previewed one is played after (none: from power-up).
    fn played_after_ui(&mut self, ui: &mut egui::Ui, project: &Plen2Project, words: &Strings) {
        let label = ui.label(words.plen2().played_after);
        let mut after = self.after;
        let name = |slot: Option<u8>| match slot {
            None => words.plen2().power_up.to_string(),
            Some(slot) => {
                let motion = project.motions.iter().find(|m| m.slot == slot);
                format!("{slot} {}", motion.map_or("", |m| m.name.as_str()))
            }
        };
        egui::ComboBox::from_id_salt("plen2-played-after")
            .selected_text(name(after))
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut after, None, name(None));
                for motion in &project.motions {
                    ui.selectable_value(&mut after, Some(motion.slot), name(Some(motion.slot)));
                }
            })
            .response
            .labelled_by(label.id)
            .on_hover_text(words.plen2().snap_note);
        self.after = after;
    }
}

/// What the robot really does with this motion where it is not what the file
/// reads as (plen2.md §6), and a robot standing elsewhere than it starts.
fn warnings(
    ui: &mut egui::Ui,
    (project, slot): (&Plen2Project, u8),
    played: &Playback,
    (settings, pose): (&Settings, &[i16; 18]),
    words: &Strings,
) {
    let first_ms =
        project.motions.iter().find(|m| m.slot == slot).and_then(|m| m.frames.first()).map(|f| f.transition_ms);
    if first_ms.is_some_and(|ms| playback::cycles_for(ms) == 0) {
        ui.colored_label(ui.visuals().error_fg_color, words.plen2().first_frame_undefined);
    }
    if !played.ended {
        ui.colored_label(ui.visuals().warn_fg_color, words.plen2().motion_never_ends);
    }
    // Where the robot stands now (the sliders) against where the motion starts.
    let mut standing = [0; DEVICE_IDS];
    for joint in Joint::ALL {
        let device = usize::from(joint.device_id());
        standing[device] = pose[joint.index()] - settings[device].0;
    }
    if playback::clamped(&standing, settings) != playback::clamped(&played.from, settings) {
        ui.colored_label(ui.visuals().warn_fg_color, words.plen2().snap_warning).on_hover_text(words.plen2().snap_note);
    }
}
