//! The editor in a test window, built one way for every ui test: the shipped
//! fonts installed (a caption's missing glyph fails the test), its own data
//! folder, and a deadline on anything waited for.

use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use egui_kittest::kittest::Queryable;
use egui_kittest::{Harness, HarnessBuilder};
use servo_studio::device::servo::ServoHandle;
use servo_studio::link::Waker;
use servo_studio::project::Project;
use servo_studio::ui::{Action, BoardLink, Plen2Ui, RflexUi, ServoBoardLink as _, ServoUi, StudioApp, Tab};

/// A test window of `size` (the shipped fonts installed), to build with a
/// state. What panels derive from the document (validation, timing, plots)
/// is computed in the frame, whatever it costs on this machine: a frame shows
/// it at once, so no test waits on a worker's clock.
pub fn builder((width, height): (f32, f32)) -> HarnessBuilder<StudioApp> {
    Harness::builder().with_size(egui::vec2(width, height)).with_context_setup(|ctx| {
        servo_studio::ui::fonts::install(ctx);
        servo_studio::ui::Costing::IN_FRAME.install(ctx);
    })
}

/// A window of `size` showing `app`.
pub fn window(app: StudioApp, size: (f32, f32)) -> Harness<'static, StudioApp> {
    builder(size).build_ui_state(|ui, app: &mut StudioApp| app.show(ui), app)
}

/// Whether the editor's threads (its board's link, its workers) said they
/// have news for the window since the test last looked: what its waker
/// does, one per test thread.
#[derive(Default)]
struct Woken {
    news: Mutex<bool>,
    told: Condvar,
}

thread_local! {
    static WOKEN: Arc<Woken> = Arc::default();
}

/// The waker an editor built here gets: it tells this test's thread.
pub fn waker() -> Waker {
    let woken = WOKEN.with(Arc::clone);
    Arc::new(move || {
        *woken.news.lock().unwrap() = true;
        woken.told.notify_all();
    })
}

/// Between two frames of a test waiting on something: until the editor's
/// threads have news, or 10 ms have passed (for what moves with time alone,
/// and for an editor built with another waker). A test waiting on a board
/// leaves the cores to the others instead of drawing frames nobody needs.
pub fn wait_for_news() {
    let at_most = Duration::from_millis(10);
    WOKEN.with(|woken| {
        let news = woken.news.lock().unwrap();
        let (mut news, _) = woken.told.wait_timeout_while(news, at_most, |news| !*news).unwrap();
        *news = false;
    });
}

/// An editor on `project`, keeping its backups and recovery file in a folder of its own.
pub fn editor(project: impl Into<Project>) -> StudioApp {
    let data = tempfile::tempdir().unwrap().keep();
    StudioApp::new(project, None, waker()).with_data_dir(data)
}

/// `app` showing `tab` in a window of `size`, after a few frames.
pub fn showing(mut app: StudioApp, tab: Tab, size: (f32, f32)) -> Harness<'static, StudioApp> {
    app.apply(Action::ShowTab(tab));
    let mut harness = window(app, size);
    harness.run_steps(3);
    harness
}

/// Runs frames until `done` holds, failing after 10 s (a board or a file
/// answers on its own thread).
pub fn run_until(harness: &mut Harness<'static, StudioApp>, what: &str, done: impl Fn(&StudioApp) -> bool) {
    let deadline = Instant::now() + Duration::from_secs(10);
    while !done(harness.state()) {
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        harness.step();
        if !done(harness.state()) {
            wait_for_news();
        }
    }
    // A connected board keeps the window repainting: it never "settles".
    harness.run_steps(3);
}

/// The connected servo board, if that is what the editor is connected to.
pub fn servo_board(app: &StudioApp) -> Option<&ServoHandle> {
    app.link.as_ref().and_then(BoardLink::servo)
}

/// Clicks "● Record" and runs frames through its 3 s count-in (the harness's
/// clock moves 250 ms a frame): the next frame is the recording's first sample.
pub fn record_through_count_in(harness: &mut Harness<'static, StudioApp>) {
    harness.get_by_label("● Record").click();
    harness.step();
    // This frame starts the count-in.
    harness.step();
    assert!(harness.query_by_label_contains("Recording in 3").is_some());
    harness.run_steps(11);
}

/// Asks the board for its servos until `done` holds for them, at most every
/// 10 ms (a servo's move is timed on the board's clock: nothing tells when it
/// ends but asking), failing after 10 s.
pub fn servos_until(
    requester: &servo_studio::device::servo::Requester,
    what: &str,
    done: impl Fn(&[servo_studio::protocol::servo::ServoStatus]) -> bool,
) {
    let deadline = Instant::now() + Duration::from_secs(10);
    let pace = crossbeam_channel::tick(Duration::from_millis(10));
    loop {
        let servos = requester.query_servos(255).unwrap();
        if done(&servos) {
            return;
        }
        assert!(Instant::now() < deadline, "timed out waiting for {what}: {servos:?}");
        let _ = pace.recv();
    }
}

/// The servo board's side of the editor.
pub fn servo_ui(app: &StudioApp) -> &ServoUi {
    app.families.of().expect("the editor has the servo family")
}

/// The servo board's side of the editor, to change.
pub fn servo_ui_mut(app: &mut StudioApp) -> &mut ServoUi {
    app.families.of_mut().expect("the editor has the servo family")
}

/// The PLEN2's side of the editor.
pub fn plen2_ui(app: &StudioApp) -> &Plen2Ui {
    app.families.of().expect("the editor has the PLEN2 family")
}

/// The rFLEX base's side of the editor.
pub fn rflex_ui(app: &StudioApp) -> &RflexUi {
    app.families.of().expect("the editor has the rFLEX family")
}

/// The open show's run log, in English, a line each (empty with no show open).
pub fn show_log(app: &StudioApp) -> Vec<String> {
    let session = app.desks.show.session.as_ref();
    session
        .map(|session| session.log(servo_studio::ui::Language::English).into_iter().map(String::from).collect())
        .unwrap_or_default()
}
