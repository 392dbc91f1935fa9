//! The servo board robot's 3D preview, from the rig its project gives: beside
//! the sliders, the live pose; beside the action editor and the macro
//! composer, the trajectory the board plays (the one the plots draw) at the
//! time cursor, with a faint ghost of where it is going next. Servos outside
//! the rig are bars beside the figure.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::figure::ik::Limb;
use crate::figure::{self, Chain, Placed, Shape};
use crate::project::{self, ServoProject};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;
use crate::ui::layout;
use crate::ui::rows;
use crate::ui::servo::action::ServoAction;
use crate::ui::servo::captions::ServoWords;
use crate::ui::shell::ShellView;
use crate::ui::transport::Transport;
use crate::ui::view3d::posing::{self, Posing};
use crate::ui::view3d::{Handle, MeshFiles, Scene, SceneMesh, Touch, View};

/// What a timed preview plays: an action's or a macro's trajectories (the
/// ones its plot draws), when it ends, and the times where a move starts or
/// ends. Derived with the plot's series, once per revision, off the frame
/// path for a large project.
#[derive(Debug, Default)]
pub struct Timed {
    trajectories: project::Trajectories,
    end_ms: f64,
    marks: Vec<f64>,
}

impl Timed {
    /// The preview of `trajectories` ending at `end_ms` (a minute at most is previewed).
    pub fn new(trajectories: project::Trajectories, end_ms: f64) -> Self {
        let end_ms = end_ms.min(60_000.0);
        let mut marks: Vec<f64> = trajectories.values().flatten().map(|(t, _)| *t).filter(|t| *t <= end_ms).collect();
        marks.sort_by(f64::total_cmp);
        marks.dedup();
        Self { trajectories, end_ms, marks }
    }
}

/// The rig as a chain: the servos it was built from, the chain, each servo's
/// link, the ground's height.
type Rig = (Vec<project::Servo>, Chain, BTreeMap<u8, usize>, f32);

/// The rig's limbs posed by their ends: the limbs, their twins, every link's limits.
type Limbs = (Vec<Limb>, Vec<Option<usize>>, Vec<(f32, f32)>);

/// The preview's state.
#[derive(Debug, Default)]
pub struct Preview {
    /// The rig's chain and each servo's link, for the servos it was built from; the ground's height.
    /// (Kept while the servos are unchanged: editing an action or a macro leaves it be.)
    rig: Option<Rig>,
    live_view: View,
    timed_view: View,
    /// The action editor's and the macro composer's time cursor.
    pub transport: Transport,
    /// What the view showed last: each servo's angle, °.
    pub shown: Option<BTreeMap<u8, f64>>,
    /// The turn last sent for the servo a drag in the live view holds (°).
    turned: Option<i32>,
    /// What the live view drew last.
    live_scene: Scene,
    /// The rig's limbs (built with the rig).
    limbs: Limbs,
    /// How they are posed.
    pub posing: Posing,
    /// The folder mesh files are relative to (the project file's).
    folder: Option<PathBuf>,
    /// The mesh files read so far.
    pub mesh_files: MeshFiles,
    /// The sound lane under the time cursor.
    pub lane: crate::ui::sound::SoundLane,
}

/// The lowest point of a scene's solids.
fn lowest(solids: &[figure::WorldSolid]) -> f32 {
    solids
        .iter()
        .map(|solid| match solid.shape {
            Shape::Box { half } => solid.at.z - half.length(),
            Shape::Ball { radius } => solid.at.z - radius,
            Shape::Capsule { to, radius } => solid.at.z.min(to.z) - radius,
        })
        .fold(0.0, f32::min)
}

/// The colour of a link drawn by its mesh.
const MESH_COLOR: [u8; 3] = [205, 208, 214];

impl Preview {
    /// The folder the project's mesh files are relative to (files read again when it changes).
    pub fn set_folder(&mut self, folder: Option<&Path>) {
        if self.folder.as_deref() != folder {
            self.folder = folder.map(Path::to_path_buf);
            self.mesh_files.clear();
        }
    }

    /// Where a mesh file of the project is.
    fn mesh_path(&self, path: &str) -> PathBuf {
        let path = Path::new(path);
        match &self.folder {
            Some(folder) if path.is_relative() => folder.join(path),
            _ => path.to_path_buf(),
        }
    }

    /// The project's meshes, on their links as `placed` puts them (those read so far).
    fn meshes(&mut self, project: &ServoProject, placed: &[Placed], ctx: &egui::Context) -> Vec<SceneMesh> {
        let Some((_, _, links, _)) = &self.rig else { return Vec::new() };
        let mut meshes = Vec::new();
        for link_mesh in &project.meshes {
            let link = match link_mesh.servo_id {
                None => 0,
                Some(id) => match links.get(&id) {
                    Some(link) => *link,
                    None => continue,
                },
            };
            let Some(on) = placed.get(link) else { continue };
            let path = self.mesh_path(&link_mesh.path);
            let Some(mesh) = self.mesh_files.get(&path, ctx) else { continue };
            let [x, y, z] = link_mesh.offset_mm.map(f32::from);
            let [rx, ry, rz] = link_mesh.rotation_deg.map(|d| f32::from(d).to_radians());
            let turn = figure::Mat3::from_euler(glam::EulerRot::ZYX, rz, ry, rx);
            let place = on.then(&Placed { position: figure::Vec3::new(x, y, z), rotation: turn });
            // Thousandths of a millimetre per unit: small whole numbers.
            #[allow(clippy::cast_precision_loss)]
            let scale = link_mesh.scale_milli as f32 / 1000.0;
            meshes.push(SceneMesh { link, mesh, place, scale, color: MESH_COLOR });
        }
        meshes
    }

    /// What could not be read of the project's mesh files.
    pub fn mesh_errors(&self, project: &ServoProject) -> Vec<String> {
        let paths: Vec<PathBuf> = project.meshes.iter().map(|mesh| self.mesh_path(&mesh.path)).collect();
        self.mesh_files.errors(paths.iter().map(PathBuf::as_path)).into_iter().map(str::to_string).collect()
    }

    fn rig(&mut self, project: &ServoProject) {
        if self.rig.as_ref().is_none_or(|(servos, ..)| *servos != project.servos) {
            let (chain, links) = figure::rig::chain(project);
            let homes = project.servos.iter().map(|s| (s.id, f64::from(s.home_deg))).collect();
            let placed = chain.pose(&figure::rig::angles(project, &links, &homes, chain.links.len()));
            let ground = lowest(&chain.dress(&placed, false));
            let (limbs, twins) = figure::rig::limbs(project, &chain, &links);
            self.limbs = (limbs, twins, figure::rig::limits(project, &links, chain.links.len()));
            self.rig = Some((project.servos.clone(), chain, links, ground));
        }
    }

    /// The figure for `degrees` (and a ghost).
    fn scene(
        &mut self,
        project: &ServoProject,
        (degrees, ghost): (&BTreeMap<u8, f64>, Option<&BTreeMap<u8, f64>>),
        (base, ctx): (Placed, &egui::Context),
    ) -> Scene {
        let Some((_, chain, links, ground)) = &self.rig else { return Scene::default() };
        let mut solids = Vec::new();
        if let Some(ghost) = ghost {
            let placed = chain.pose_from(base, &figure::rig::angles(project, links, ghost, chain.links.len()));
            solids.extend(chain.dress(&placed, true));
        }
        let placed = chain.pose_from(base, &figure::rig::angles(project, links, degrees, chain.links.len()));
        solids.extend(chain.dress(&placed, false));
        let ground_z = *ground;
        let meshes = self.meshes(project, &placed, ctx);
        Scene { solids, ground_z, meshes, ..Scene::default() }
    }

    /// The servo a link of the figure is.
    fn servo_of(&self, link: usize) -> Option<u8> {
        let (_, _, links, _) = self.rig.as_ref()?;
        links.iter().find(|(_, index)| **index == link).map(|(id, _)| *id)
    }

    /// The view and, beside it, a bar per servo outside the rig; what touching the view did.
    fn draw(&mut self, ui: &mut egui::Ui, project: &ServoProject, scene: &Scene, live: bool, words: &Strings) -> Touch {
        let degrees = self.shown.clone().unwrap_or_default();
        let outside: Vec<&project::Servo> = project.servos.iter().filter(|servo| servo.rig.is_none()).collect();
        let rigged = self.rig.as_ref().is_some_and(|(_, chain, ..)| chain.links.len() > 1);
        let bars = |ui: &mut egui::Ui| {
            ui.label(words.servo().not_rigged).on_hover_text(words.servo().rig_hint);
            let height = ui.available_height();
            rows::list(ui, "unrigged-servos", rows::name_row_height(ui), outside.len(), height, |ui, index| {
                let servo = outside[index];
                let angle = degrees.get(&servo.id).copied().unwrap_or(f64::from(servo.home_deg));
                let span = f64::from(servo.max_deg - servo.min_deg).max(1.0);
                // A fraction for a bar.
                #[allow(clippy::cast_possible_truncation)]
                let fraction = ((angle - f64::from(servo.min_deg)) / span).clamp(0.0, 1.0) as f32;
                let text = format!("{} {:.0}°", servo.id, angle);
                ui.add(egui::ProgressBar::new(fraction).text(text).desired_height(rows::name_row_height(ui) - 2.0))
                    .on_hover_text(&servo.caption);
            });
        };
        if !rigged {
            ui.label(words.servo().rig_hint);
            bars(ui);
            return Touch::default();
        }
        let mut touch = Touch::default();
        for error in self.mesh_errors(project) {
            ui.colored_label(ui.visuals().error_fg_color, format!("{error} — {}", words.servo().mesh_error_hint));
        }
        let view = if live { &mut self.live_view } else { &mut self.timed_view };
        let mut figure = |ui: &mut egui::Ui| {
            let rect = ui.available_rect_before_wrap();
            let (response, touched) = view.show(ui, rect, scene, words.robot_preview);
            if touched.hovered.is_none() {
                response.on_hover_text(words.preview_hint);
            }
            touch = touched;
        };
        if outside.is_empty() {
            figure(ui);
            return touch;
        }
        let mut width = 150.0;
        layout::columns(ui, "preview-bars", &mut width, 100.0, |ui, pane| match pane {
            layout::Pane::First => bars(ui),
            layout::Pane::Second => figure(ui),
        });
        touch
    }

    /// The live pose beside the sliders, to be posed by touching it: hovering
    /// a servo's link names it and its angle, a click selects it, a drag turns it.
    pub fn live(
        &mut self,
        ui: &mut egui::Ui,
        (project, pose): (&ServoProject, &BTreeMap<u8, i16>),
        selected: Option<u8>,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        self.rig(project);
        let degrees: BTreeMap<u8, f64> = pose.iter().map(|(id, degree)| (*id, f64::from(*degree))).collect();
        let Some((_, chain, links, _)) = &self.rig else { return };
        let angles = figure::rig::angles(project, links, &degrees, chain.links.len());
        let base = {
            let (limbs, twins, limits) = &self.limbs;
            let rig = posing::Rig { chain, limbs, twins, limits, mm_per_unit: 1.0 };
            if !limbs.is_empty() {
                self.posing.toolbar(ui, limbs, &mut self.live_view, words.lang);
            }
            self.posing.base(&rig, &angles)
        };
        let mut scene = self.scene(project, (&degrees, None), (base, &ui.ctx().clone()));
        let Some((_, chain, links, _)) = &self.rig else { return };
        let (limbs, twins, limits) = &self.limbs;
        let rig = posing::Rig { chain, limbs, twins, limits, mm_per_unit: 1.0 };
        let placed = chain.pose_from(base, &angles);
        scene.ends = self.posing.ends(&rig, &placed, words.lang);
        scene.gap = self.posing.gap();
        scene.handles = (0..chain.links.len())
            .map(|link| {
                let servo = project.servo(self.servo_of(link)?)?;
                let angle = pose.get(&servo.id).copied().unwrap_or(servo.home_deg);
                let reading = format!("{} #{}  {angle}°", servo.caption, servo.id);
                Some(Handle { reading, joint: chain.joint(&placed, link) })
            })
            .collect();
        scene.selected = selected.and_then(|id| links.get(&id).copied());
        self.shown = Some(degrees);
        let touch = self.draw(ui, project, &scene, true, words);
        self.live_scene = scene;
        self.posed(project, (&angles, base), &touch, words, actions);
        if let Some(servo_id) = touch.clicked.and_then(|link| self.servo_of(link)) {
            actions.push(Action::family(ServoAction::SelectServo(Some(servo_id))));
        }
        // A servo's angle turns its link by as many degrees (its axis carries `reversed`).
        if let Some((link, by_deg)) = touch.new_turn(&mut self.turned, 1.0)
            && let Some(servo_id) = self.servo_of(link)
        {
            actions.push(Action::family(ServoAction::TurnServo { servo_id, by_deg }));
        }
        if touch.let_go.is_some() {
            actions.push(Action::family(ServoAction::TurnDone));
        }
    }

    /// What a drag on a hand's or a foot's ring asks for: the servos that reach it.
    fn posed(
        &mut self,
        project: &ServoProject,
        (angles, base): (&[f32], Placed),
        touch: &Touch,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let Some((_, chain, links, _)) = &self.rig else { return };
        let (limbs, twins, limits) = &self.limbs;
        let rig = posing::Rig { chain, limbs, twins, limits, mm_per_unit: 1.0 };
        let posed = self.posing.reach(&rig, angles, base, touch, words.lang);
        if let Some(solved) = posed.angles {
            actions.push(Action::family(ServoAction::Pose(figure::rig::degrees(project, links, &solved))));
        }
        if posed.done {
            actions.push(Action::family(ServoAction::TurnDone));
        }
    }

    #[cfg(any(test, feature = "test-api"))]
    /// How many meshes the live view drew last.
    pub fn meshes_drawn(&self) -> usize {
        self.live_scene.meshes.len()
    }

    /// Where on the screen an end (a limb's, in the rig's order; then the
    /// pelvis) was last drawn in the live view.
    pub fn end_on_screen(&self, end: usize) -> Option<egui::Pos2> {
        self.live_view.on_screen(self.live_scene.ends.get(end)?.at)
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Where on the screen a point of `servo_id`'s link was last drawn in the
    /// live view (the one farthest from its axis), to touch it there.
    pub fn servo_on_screen(&self, servo_id: u8) -> Option<egui::Pos2> {
        let (_, _, links, _) = self.rig.as_ref()?;
        let grip = crate::ui::view3d::grip(&self.live_scene, *links.get(&servo_id)?)?;
        self.live_view.on_screen(grip)
    }

    /// An action's or a macro's trajectory at the time cursor, with the pose
    /// at its next mark as a ghost.
    pub fn timed(
        &mut self,
        ui: &mut egui::Ui,
        project: &ServoProject,
        timed: &Timed,
        (view, actions): (&ShellView<'_>, &mut Vec<Action>),
    ) {
        let words = view.language.strings();
        self.rig(project);
        self.transport.ui(ui, view.sound.span_ms(timed.end_ms), &timed.marks, words);
        let cursor = (&mut self.transport, timed.end_ms, &timed.marks[..]);
        self.lane.ui(ui, view.sound, cursor, view.language, actions);
        let at = |t: f64| -> BTreeMap<u8, f64> {
            // The board updates its servos every 10 ms: the nearest update.
            let step = (t / project::SAMPLE_MS).round().clamp(0.0, (timed.end_ms / project::SAMPLE_MS).ceil());
            let angles = project::pose_at(project, &timed.trajectories, step * project::SAMPLE_MS);
            project.servos.iter().map(|servo| servo.id).zip(angles).collect()
        };
        let t = self.transport.t_ms;
        let degrees = at(t);
        let next = timed.marks.iter().find(|mark| **mark > t + 1.0).copied();
        let ghost = next.map(at);
        let scene = self.scene(project, (&degrees, ghost.as_ref()), (Placed::ORIGIN, &ui.ctx().clone()));
        self.shown = Some(degrees);
        self.draw(ui, project, &scene, false, words);
    }
}
