//! Names the commit a binary was built from, for `servo-studio --version`:
//! `SERVO_STUDIO_COMMIT` is `commit` and git's short hash, or `unknown
//! commit` outside a git checkout (a source tarball) or without git.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let output = Command::new("git").args(args).output().ok()?;
    let said = String::from_utf8_lossy(&output.stdout).trim().to_string();
    (output.status.success() && !said.is_empty()).then_some(said)
}

fn main() {
    let commit = git(&["rev-parse", "--short=12", "HEAD"])
        .map_or_else(|| "unknown commit".into(), |hash| format!("commit {hash}"));
    println!("cargo:rustc-env=SERVO_STUDIO_COMMIT={commit}");
    // A new commit or another branch checked out changes what is named.
    println!("cargo:rerun-if-changed=.git/HEAD");
    if let Some(branch) = git(&["symbolic-ref", "-q", "HEAD"]) {
        println!("cargo:rerun-if-changed=.git/{branch}");
    }
}
