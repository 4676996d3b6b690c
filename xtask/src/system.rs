//! What several xtask commands need of the machine: Debian packages installed with apt-get when
//! missing, and the release `clr` binary.

use std::path::PathBuf;
use std::process::Command;

use crate::{target_dir, workspace_root};

/// The full path of `program` on the PATH.
pub fn which(program: &str) -> Option<PathBuf> {
    Command::new("which")
        .arg(program)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| PathBuf::from(String::from_utf8_lossy(&o.stdout).trim()))
}

/// Install the Debian `packages` with apt-get unless every program of `programs` is on the
/// PATH already (`who` names the command in the messages).
///
/// # Errors
/// apt-get missing or failing (it needs root), or a program still missing after it.
pub fn apt_install(who: &str, packages: &[&str], programs: &[&str]) -> Result<(), String> {
    if programs.iter().all(|p| which(p).is_some()) {
        return Ok(());
    }
    let list = packages.join(" ");
    eprintln!("{who}: installing Debian's {list} with apt-get");
    for args in [
        &["update", "-q"][..],
        &[&["install", "-y", "-q"][..], packages].concat()[..],
    ] {
        let ok = Command::new("apt-get")
            .args(args)
            .env("DEBIAN_FRONTEND", "noninteractive")
            .status()
            .map_err(|e| format!("apt-get: {e}; install {list} yourself"))?
            .success();
        if !ok {
            return Err(format!(
                "apt-get could not install {list} (needs root); install them yourself"
            ));
        }
    }
    match programs.iter().find(|p| which(p).is_none()) {
        Some(p) => Err(format!("{p} still not on the PATH after apt-get")),
        None => Ok(()),
    }
}

/// Build the release `clr` and return its path.
///
/// # Errors
/// The build failed.
pub fn build_clr() -> Result<PathBuf, String> {
    let ok = Command::new(env!("CARGO"))
        .args(["build", "--release", "--bin", "clr"])
        .current_dir(workspace_root())
        .status()
        .map_err(|e| format!("cargo build: {e}"))?
        .success();
    if !ok {
        return Err("cargo build --release --bin clr failed".into());
    }
    let p = target_dir().join("release").join("clr");
    std::path::absolute(&p).map_err(|e| format!("{}: {e}", p.display()))
}
