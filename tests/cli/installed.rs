//! What the Debian package installs beside the binary (`docs/install.md`),
//! checked: the man pages and shell completions kept in `assets/` are what the
//! command line makes of its own definitions now; each is well formed (mandoc,
//! `bash -n`, `zsh -n`, `fish -n`); the desktop entry passes
//! `desktop-file-validate`; the MIME types tell a project and a show file from
//! other JSON by their content (`update-mime-database`, `gio`); every asset the
//! package lists is there; `--version` names the commit. A tool that is not
//! installed skips its check with a notice (CI installs them all and requires them).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

fn here(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// Whether `tool` runs here; a notice (or, where required, a failure) when it does not.
fn have(tool: &str, package: &str) -> bool {
    let found =
        Command::new("sh").args(["-c", &format!("command -v {tool}")]).output().is_ok_and(|o| o.status.success());
    if !found {
        common::without_service(&format!("{tool} is not installed"), &format!("apt-get install {package}"));
    }
    found
}

fn run(program: &str, args: &[&str]) -> (bool, String) {
    let output = Command::new(program).args(args).output().unwrap();
    let said = format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    (output.status.success(), said)
}

#[test]
fn the_man_pages_kept_are_the_command_lines_own_and_well_formed() {
    let made = tempfile::tempdir().unwrap();
    let (ok, said) = run(EXE, &["man", "--out", made.path().to_str().unwrap()]);
    assert!(ok, "{said}");
    let names = |folder: &Path| {
        let mut names: Vec<String> = std::fs::read_dir(folder)
            .unwrap()
            .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    let kept = here("assets/man");
    assert_eq!(
        names(made.path()),
        names(&kept),
        "assets/man is stale: cargo run -- man --out assets/man (after removing the old pages)"
    );
    for name in names(&kept) {
        let (now, before) = (std::fs::read(made.path().join(&name)).unwrap(), std::fs::read(kept.join(&name)).unwrap());
        assert!(now == before, "assets/man/{name} is stale: cargo run -- man --out assets/man");
    }
    for wanted in ["servo-studio.1", "servo-studio-serve.1", "servo-studio-rflex-drive.1", "servo-studio-board-info.1"]
    {
        assert!(names(&kept).contains(&wanted.to_string()), "{wanted}");
    }
    if have("mandoc", "mandoc") {
        for name in names(&kept) {
            let (ok, said) = run("mandoc", &["-T", "lint", "-W", "error", kept.join(&name).to_str().unwrap()]);
            assert!(ok && said.is_empty(), "{name}: {said}");
        }
    }
}

#[test]
fn the_completions_kept_are_the_command_lines_own_and_each_shell_reads_them() {
    for (shell, file, checker, package) in [
        ("bash", "servo-studio.bash", "bash", "bash"),
        ("zsh", "_servo-studio", "zsh", "zsh"),
        ("fish", "servo-studio.fish", "fish", "fish"),
    ] {
        let made = Command::new(EXE).args(["completions", shell]).output().unwrap();
        assert!(made.status.success());
        let kept = here(&format!("assets/completions/{file}"));
        assert!(
            made.stdout == std::fs::read(&kept).unwrap(),
            "assets/completions/{file} is stale: cargo run -- completions {shell} > assets/completions/{file}"
        );
        assert!(String::from_utf8_lossy(&made.stdout).contains("serve"), "{shell}: the subcommands are there");
        if have(checker, package) {
            let (ok, said) = run(checker, &["-n", kept.to_str().unwrap()]);
            assert!(ok, "{shell}: {said}");
        }
    }
}

#[test]
fn the_desktop_entry_is_valid_and_opens_both_kinds_of_file() {
    let entry = std::fs::read_to_string(here("assets/servo-studio.desktop")).unwrap();
    assert!(entry.contains("Exec=servo-studio gui %f") && entry.contains("Icon=servo-studio"), "{entry}");
    assert!(entry.contains("application/x-servo-studio-project;application/x-servo-studio-show;"), "{entry}");
    if have("desktop-file-validate", "desktop-file-utils") {
        let (ok, said) = run("desktop-file-validate", &[here("assets/servo-studio.desktop").to_str().unwrap()]);
        assert!(ok && said.trim().is_empty(), "{said}");
    }
}

#[test]
fn the_mime_types_tell_a_project_and_a_show_from_other_json_by_their_content() {
    if !have("update-mime-database", "shared-mime-info") || !have("gio", "libglib2.0-bin") {
        return;
    }
    let data = tempfile::tempdir().unwrap();
    let packages = data.path().join("mime/packages");
    std::fs::create_dir_all(&packages).unwrap();
    std::fs::copy(here("assets/mime/servo-studio.xml"), packages.join("servo-studio.xml")).unwrap();
    let (ok, said) = run("update-mime-database", &[data.path().join("mime").to_str().unwrap()]);
    assert!(ok, "{said}");
    let files = tempfile::tempdir().unwrap();
    let show = files.path().join("show.json");
    let mut a_show = servo_studio::show::Show::of_one(
        "skull",
        servo_studio::project::Project::empty(servo_studio::project::Family::Servo),
    );
    a_show.cues.clear();
    std::fs::write(&show, a_show.to_json()).unwrap();
    let other = files.path().join("other.json");
    std::fs::write(&other, "{\"format\": \"something else\"}\n").unwrap();
    for (file, wanted) in [
        (here("tests/fixtures/project-v2.json"), "application/x-servo-studio-project"),
        (show, "application/x-servo-studio-show"),
        (other, "application/json"),
    ] {
        let output = Command::new("gio")
            .args(["info", "--attributes=standard::content-type", file.to_str().unwrap()])
            .env("XDG_DATA_HOME", data.path())
            .env("XDG_DATA_DIRS", "/usr/share")
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&output.stdout);
        assert!(said.contains(&format!("standard::content-type: {wanted}\n")), "{}: {said}", file.display());
    }
}

#[test]
fn every_asset_the_package_lists_is_there_and_installs_under_usr_or_lib() {
    let manifest: toml::Table = toml::from_str(&std::fs::read_to_string(here("Cargo.toml")).unwrap()).unwrap();
    let deb = &manifest["package"]["metadata"]["deb"];
    let assets = deb["assets"].as_array().unwrap();
    for asset in assets {
        let [source, destination, mode] = asset.as_array().unwrap().as_slice() else { panic!("{asset:?}") };
        let (source, destination, mode) =
            (source.as_str().unwrap(), destination.as_str().unwrap(), mode.as_str().unwrap());
        assert!(destination.starts_with("usr/") || destination.starts_with("lib/udev/rules.d/"), "{destination}");
        assert!(mode == "644" || (mode == "755" && destination == "usr/bin/"), "{source}: {mode}");
        if source.starts_with("target/") {
            continue;
        }
        if let Some(folder) = source.strip_suffix("/*.1") {
            assert!(std::fs::read_dir(here(folder)).unwrap().count() > 10, "{source}");
        } else {
            assert!(here(source).is_file(), "{source} is listed but missing");
        }
    }
    // The icon at every size the hicolor theme asks the package for, each the size it says.
    for size in [16, 22, 24, 32, 48, 64, 128, 256, 512] {
        let png = std::fs::read(here(&format!("assets/icons/servo-studio-{size}.png"))).unwrap();
        let (width, height) =
            (u32::from_be_bytes(png[16..20].try_into().unwrap()), u32::from_be_bytes(png[20..24].try_into().unwrap()));
        assert_eq!((width, height), (size, size), "servo-studio-{size}.png");
    }
    // The maintainer scripts only reload udev and say how the ports are shared: nothing left behind.
    for script in ["postinst", "postrm"] {
        let text = std::fs::read_to_string(here(&format!("assets/debian/{script}"))).unwrap();
        assert!(!text.contains("mkdir") && !text.contains("cp ") && !text.contains("> /"), "{script} writes nothing");
    }
    let rules = std::fs::read_to_string(here("assets/udev/60-servo-studio.rules")).unwrap();
    for rule in rules.lines().filter(|line| !line.trim().is_empty() && !line.starts_with('#')) {
        assert!(
            rule.starts_with("SUBSYSTEM==\"tty\", ATTRS{idVendor}==") && rule.ends_with("TAG+=\"uaccess\""),
            "{rule}"
        );
    }
}

#[test]
fn the_version_names_the_commit_it_was_built_from() {
    let (ok, said) = run(EXE, &["--version"]);
    assert!(ok, "{said}");
    let commit = Command::new("git").args(["rev-parse", "--short=12", "HEAD"]).current_dir(here(".")).output();
    match commit {
        Ok(output) if output.status.success() => {
            let hash = String::from_utf8_lossy(&output.stdout).trim().to_string();
            assert_eq!(said.trim(), format!("servo-studio {} (commit {hash})", env!("CARGO_PKG_VERSION")));
        }
        // Not a git checkout (a source tarball): said so.
        _ => assert!(said.contains("unknown commit"), "{said}"),
    }
}
