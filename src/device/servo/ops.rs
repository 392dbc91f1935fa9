//! Operations on a servo board: read it whole (export / backup), write a
//! project onto it (import, with validation, a fit check, a backup and a
//! verification), and read its status. Each reports progress and can be
//! cancelled between steps.

use std::path::{Path, PathBuf};

use super::client::Requester;
use super::image::{ImageError, ServoImage};
use super::item::Item;
use super::session::RequestError;
use crate::device::{Cancel, UploadFailure};
use crate::project::{self, Problems, Project, SaveError, ServoProject};
use crate::protocol::servo::{ALL_SERVOS, EncodeError, Message, ServoStatus};

pub use crate::device::Phase;

/// How far a servo-board operation has come.
pub type Progress = crate::device::Progress<Item>;

fn check(cancel: &Cancel) -> Result<(), OpError> {
    if cancel.is_requested() { Err(OpError::Cancelled) } else { Ok(()) }
}

/// An operation failed. Each message says what failed and what to try.
#[derive(Debug, thiserror::Error)]
pub enum OpError {
    /// A request got no usable response.
    #[error("{item}: {source}")]
    Request {
        /// What was being done.
        item: Item,
        /// Why it failed.
        source: RequestError,
    },
    /// The board answered `result = 0`.
    #[error("{item}: the board refused it (result 0). Is its memory full, or the item malformed?")]
    Refused {
        /// What was refused.
        item: Item,
    },
    /// The board answered a query with its "failure" value.
    #[error("{item}: the board reported a failure reading it")]
    ReadFailed {
        /// What could not be read.
        item: Item,
    },
    /// The project has validation errors; nothing was written.
    #[error(
        "the project has {} error(s); nothing was written:\n{}\nFix them, or restore it as it is with `import --force` (Upload anyway in the editor)",
        .problems.errors(),
        .problems.listed(20)
    )]
    Invalid {
        /// The errors.
        problems: Problems,
    },
    /// The project is larger than the board's memory; nothing was written.
    #[error(
        "the project needs {needed_bytes} bytes but the board holds {total_bytes}; nothing was written. Remove actions or macros"
    )]
    DoesNotFit {
        /// Bytes the project needs.
        needed_bytes: usize,
        /// The board's total memory.
        total_bytes: i64,
    },
    /// The project cannot be turned into board records.
    #[error(transparent)]
    Image(#[from] ImageError),
    /// A record cannot be encoded.
    #[error(transparent)]
    Encode(#[from] EncodeError),
    /// The backup could not be saved; nothing was written.
    #[error("backup failed, so nothing was written: {0}")]
    Backup(SaveError),
    /// What the board holds after writing differs from the project.
    #[error("verification failed: the board differs from the project:\n{}", list(.differences))]
    Verify {
        /// Each difference.
        differences: Vec<super::image::Difference>,
    },
    /// The owner cancelled.
    #[error("cancelled")]
    Cancelled,
    /// A response of the wrong kind (a protocol error by the board).
    #[error("{item}: unexpected response {response}")]
    Unexpected {
        /// What was being done.
        item: Item,
        /// The response's name.
        response: &'static str,
    },
}

fn list<T: std::fmt::Display>(items: &[T]) -> String {
    items.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n")
}

struct Run<'a> {
    requester: &'a Requester,
    progress: &'a mut dyn FnMut(&Progress),
    cancel: &'a Cancel,
    phase: Phase,
    done: usize,
    total: usize,
}

impl Run<'_> {
    fn step(&mut self, item: Item, message: Message) -> Result<Message, OpError> {
        check(self.cancel)?;
        (self.progress)(&Progress { phase: self.phase, done: self.done, total: self.total, item: item.clone() });
        let response =
            self.requester.request(message).map_err(|source| OpError::Request { item: item.clone(), source })?;
        self.done += 1;
        (self.progress)(&Progress { phase: self.phase, done: self.done, total: self.total, item });
        Ok(response)
    }

    /// A write step whose response carries `result`.
    fn write(&mut self, item: Item, message: Message) -> Result<(), OpError> {
        let response = self.step(item.clone(), message)?;
        match response.result() {
            Some(true) => Ok(()),
            Some(false) => Err(OpError::Refused { item }),
            None => Err(OpError::Unexpected { item, response: response.name() }),
        }
    }
}

fn unexpected(item: &Item, response: &Message) -> OpError {
    OpError::Unexpected { item: item.clone(), response: response.name() }
}

/// Reads everything the board stores, in the order of the export conversation:
/// project id → servo parameters → action list, each action → macro list, each
/// macro → joystick table list, each table → the active table.
pub fn read_image(
    requester: &Requester,
    progress: &mut dyn FnMut(&Progress),
    cancel: &Cancel,
) -> Result<ServoImage, OpError> {
    read_image_as(requester, Phase::Read, progress, cancel)
}

fn read_image_as(
    requester: &Requester,
    phase: Phase,
    progress: &mut dyn FnMut(&Progress),
    cancel: &Cancel,
) -> Result<ServoImage, OpError> {
    use Message as M;
    let mut run = Run { requester, progress, cancel, phase, done: 0, total: 6 };
    let mut image = ServoImage::default();

    let item = Item::ProjectId;
    image.project_id = match run.step(item.clone(), M::QueryProjectIdRequest)? {
        M::QueryProjectIdResponse { project_id } => project_id,
        other => return Err(unexpected(&item, &other)),
    };
    let item = Item::ServoParameters;
    image.servos = match run.step(item.clone(), M::QueryServoParameterRequest)? {
        M::QueryServoParameterResponse { servos } => servos,
        other => return Err(unexpected(&item, &other)),
    };

    let item = Item::ActionList;
    let actions = match run.step(item.clone(), M::QueryActionListRequest)? {
        M::QueryActionListResponse { actions } => actions,
        other => return Err(unexpected(&item, &other)),
    };
    run.total += actions.len();
    for entry in actions {
        let item = Item::Action { id: entry.id, caption: entry.caption.clone() };
        match run.step(item.clone(), M::QueryActionRequest { action_id: entry.id })? {
            M::QueryActionResponse { action: Some(action) } => image.actions.push(action),
            M::QueryActionResponse { action: None } => return Err(OpError::ReadFailed { item }),
            other => return Err(unexpected(&item, &other)),
        }
    }

    let item = Item::MacroList;
    let macros = match run.step(item.clone(), M::QueryMacroListRequest)? {
        M::QueryMacroListResponse { macros } => macros,
        other => return Err(unexpected(&item, &other)),
    };
    run.total += macros.len();
    for entry in macros {
        let item = Item::Macro { id: entry.id, caption: entry.caption.clone() };
        match run.step(item.clone(), M::QueryMacroRequest { macro_id: entry.id })? {
            M::QueryMacroResponse { macro_record: Some(record) } => image.macros.push(record),
            M::QueryMacroResponse { macro_record: None } => {
                return Err(OpError::ReadFailed { item });
            }
            other => return Err(unexpected(&item, &other)),
        }
    }

    let item = Item::TableList;
    let tables = match run.step(item.clone(), M::QueryJoystickTableListRequest)? {
        M::QueryJoystickTableListResponse { tables } => tables,
        other => return Err(unexpected(&item, &other)),
    };
    run.total += tables.len();
    for entry in tables {
        let item = Item::Table { id: entry.id, caption: entry.caption.clone() };
        match run.step(item.clone(), M::QueryJoystickTableRequest { table_id: entry.id })? {
            M::QueryJoystickTableResponse { table: Some(table) } => image.tables.push(table),
            M::QueryJoystickTableResponse { table: None } => {
                return Err(OpError::ReadFailed { item });
            }
            other => return Err(unexpected(&item, &other)),
        }
    }

    let item = Item::ActiveTable;
    image.active_table = match run.step(item.clone(), M::QueryActiveJoystickTableRequest)? {
        M::QueryActiveJoystickTableResponse { table_id } => table_id,
        other => return Err(unexpected(&item, &other)),
    };
    Ok(image)
}

/// Reads the whole board into a project.
pub fn export(
    requester: &Requester,
    progress: &mut dyn FnMut(&Progress),
    cancel: &Cancel,
) -> Result<ServoProject, OpError> {
    Ok(read_image(requester, progress, cancel)?.to_project())
}

/// How to import.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ImportOptions {
    /// Folder for the backup of the board's current contents; `None` = no backup.
    pub backup_dir: Option<PathBuf>,
    /// Read everything back afterwards and compare.
    pub verify: bool,
    /// Write even when validation finds errors (restoring a backup holding
    /// content Servo Studio would not author). What cannot be encoded at all
    /// is still refused.
    pub force: bool,
}

/// What an import did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ImportReport {
    /// Where the board's previous contents were saved.
    pub backup: Option<PathBuf>,
    /// How many write requests were acknowledged.
    pub written: usize,
    /// Whether the read-back matched exactly.
    pub verified: bool,
    /// What baking the project's curves cost, when it had any.
    pub curves: Option<CurveCost>,
}

/// How closely the board plays a project's curves baked into straight steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CurveCost {
    /// The tolerance used, tenths of a degree (above 10 when widened to fit the board).
    pub tolerance_tenths: u32,
    /// The largest distance from a curve at any 10 ms update, tenths of a degree (rounded up).
    pub max_error_tenths: u32,
}

impl CurveCost {
    /// The cost of `baked`, none when it baked no curve.
    fn of(baked: &crate::authoring::bake_servo::BakedServo) -> Option<Self> {
        // Tenths of a few hundred degrees at most.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let tenths = |deg: f64| (deg * 10.0 - 1e-9).ceil().max(0.0) as u32;
        (baked.added_actions > 0).then(|| Self {
            tolerance_tenths: tenths(baked.tolerance_deg),
            max_error_tenths: tenths(baked.max_error_deg),
        })
    }

    /// True when the tolerance was widened from 1° to fit the board's memory.
    pub fn widened(&self) -> bool {
        self.tolerance_tenths > 10
    }
}

/// The file name a backup gets: `board-backup-YYYYMMDD-HHMMSS-project<ID>.json`,
/// local time, with a counter if that name is taken.
pub fn backup_path(folder: &Path, project_id: i32) -> PathBuf {
    crate::device::backup_path(folder, "board-backup", &format!("-project{project_id}"))
}

/// A failed import: the error, and what it left on the board.
pub type ImportFailure = UploadFailure<OpError, Item>;

/// Writes `project` onto the board. Before anything is cleared: validates it
/// (errors stop the import unless `force`), checks that it fits the board's memory, and saves
/// a backup of the board. Then clears and writes in the order of the import
/// conversation, and verifies by reading everything back. A failure says what
/// it left: nothing written, the items that reached the board, or everything.
pub fn import(
    requester: &Requester,
    project: &ServoProject,
    options: &ImportOptions,
    progress: &mut dyn FnMut(&Progress),
    cancel: &Cancel,
) -> Result<ImportReport, Box<ImportFailure>> {
    let steps = Upload {
        requester,
        project,
        options,
        progress,
        cancel,
        image: ServoImage::default(),
        curves: None,
        written: 0,
        total: 0,
    };
    crate::device::upload(steps)
}

/// A servo board's upload, step by step (run by [`crate::device::upload`]).
struct Upload<'a> {
    requester: &'a Requester,
    project: &'a ServoProject,
    options: &'a ImportOptions,
    progress: &'a mut dyn FnMut(&Progress),
    cancel: &'a Cancel,
    /// The records to write (made by the check).
    image: ServoImage,
    /// What baking the curves cost (made by the check).
    curves: Option<CurveCost>,
    written: usize,
    total: usize,
}

impl crate::device::UploadSteps for Upload<'_> {
    type Error = OpError;
    type Item = Item;
    type Report = ImportReport;

    fn check(&mut self) -> Result<(), OpError> {
        use Message as M;
        let problems = project::validate_servo(self.project).errors_only();
        if problems.has_errors() && !self.options.force {
            return Err(OpError::Invalid { problems });
        }
        // The fit check reads; the write phase proper starts after the backup.
        let mut run = Run {
            requester: self.requester,
            progress: &mut *self.progress,
            cancel: self.cancel,
            phase: Phase::Read,
            done: 0,
            total: 1,
        };
        let item = Item::MemorySize;
        let total_bytes = match run.step(item.clone(), M::QueryMemorySizeRequest)? {
            // Boards that report only the free size: after clearing, free is all there is.
            M::QueryMemorySizeResponse { free_bytes, total_bytes } => i64::from(total_bytes.unwrap_or(free_bytes)),
            other => return Err(unexpected(&item, &other)),
        };
        // Curves baked to fit the board: the tolerance widens rather than the upload failing.
        let (image, baked) = ServoImage::within(self.project, Some(total_bytes))?;
        self.image = image;
        self.curves = CurveCost::of(&baked);
        let needed_bytes = self.image.footprint_bytes()?;
        if i64::try_from(needed_bytes).unwrap_or(i64::MAX) > total_bytes {
            return Err(OpError::DoesNotFit { needed_bytes, total_bytes });
        }
        Ok(())
    }

    fn back_up(&mut self) -> Result<Option<PathBuf>, OpError> {
        let Some(folder) = &self.options.backup_dir else { return Ok(None) };
        let previous = read_image_as(self.requester, Phase::Read, &mut *self.progress, self.cancel)?.to_project();
        let path = backup_path(folder, previous.project_id);
        project::save(&path, &Project::servo(previous)).map_err(OpError::Backup)?;
        Ok(Some(path))
    }

    fn write(&mut self, reached: &mut Vec<Item>) -> Result<(), OpError> {
        let mut run = Run {
            requester: self.requester,
            progress: &mut *self.progress,
            cancel: self.cancel,
            phase: Phase::Write,
            done: 0,
            total: 0,
        };
        // Even with nothing acknowledged, the clear may have run: a failure leaves the board half written.
        let written = write_image(&mut run, &self.image, reached);
        (self.written, self.total) = (run.done, run.total);
        written
    }

    fn total(&self) -> usize {
        self.total
    }

    fn verify(&mut self) -> Result<(), OpError> {
        if !self.options.verify {
            return Ok(());
        }
        let actual = read_image_as(self.requester, Phase::Verify, &mut *self.progress, self.cancel)?;
        let differences = self.image.differences(&actual);
        if differences.is_empty() { Ok(()) } else { Err(OpError::Verify { differences }) }
    }

    fn report(self, backup: Option<PathBuf>) -> ImportReport {
        ImportReport { backup, written: self.written, verified: self.options.verify, curves: self.curves }
    }
}

/// Clears the board and writes `image` in the order of the import
/// conversation; `reached` collects each item the board acknowledged.
fn write_image(run: &mut Run<'_>, image: &ServoImage, reached: &mut Vec<Item>) -> Result<(), OpError> {
    use Message as M;
    run.total = 2
        + usize::from(!image.servos.is_empty())
        + image.actions.len()
        + image.macros.len()
        + image.tables.len()
        + usize::from(image.active_table != 0);
    let mut write = |run: &mut Run<'_>, item: Item, message: Message| {
        run.write(item.clone(), message)?;
        reached.push(item);
        Ok::<(), OpError>(())
    };
    write(run, Item::ClearAll, M::ClearAllDataRequest)?;
    write(run, Item::WriteProjectId(image.project_id), M::WriteProjectIdRequest { project_id: image.project_id })?;
    if !image.servos.is_empty() {
        let servos = image.servos.clone();
        write(run, Item::AddServoParameters(servos.len()), M::AddServoParameterRequest { servos })?;
    }
    for action in &image.actions {
        let item = Item::Action { id: action.action_id, caption: action.caption.clone() };
        write(run, item, M::AddActionRequest(action.clone()))?;
    }
    for record in &image.macros {
        let item = Item::Macro { id: record.macro_id, caption: record.caption.clone() };
        write(run, item, M::AddMacroRequest(record.clone()))?;
    }
    for table in &image.tables {
        let item = Item::Table { id: table.table_id, caption: table.caption.clone() };
        write(run, item, M::AddJoystickTableRequest(table.clone()))?;
    }
    if image.active_table != 0 {
        let table_id = image.active_table;
        write(run, Item::SetActiveTable(table_id), M::SetActiveJoystickTableRequest { table_id })?;
    }
    Ok(())
}

/// A board's status at a glance.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ServoInfo {
    /// `projectID` (0 = none).
    pub project_id: i32,
    /// Free memory in bytes.
    pub free_bytes: i32,
    /// Total memory in bytes, if the board reports it.
    pub total_bytes: Option<i32>,
    /// Battery in ‰.
    pub battery_permil: i16,
    /// Every attached servo's state.
    pub servos: Vec<ServoStatus>,
}

/// Reads project id, memory, battery and the servos' states.
pub fn board_info(requester: &Requester) -> Result<ServoInfo, OpError> {
    let project_id = requester.project_id()?;
    let (free_bytes, total_bytes) = requester.memory()?;
    let battery_permil = requester.battery_permil()?;
    let servos = requester.query_servos(ALL_SERVOS)?;
    Ok(ServoInfo { project_id, free_bytes, total_bytes, battery_permil, servos })
}
