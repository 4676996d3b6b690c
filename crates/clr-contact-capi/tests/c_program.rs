//! Compiles `tests/c/test_capi.c` with the machine's C compiler (`cc`, or `$CC`), links it
//! against the static library built for this test run, runs it and requires every check to pass.
//! The C program compares against contact-laws.md §7 with the tolerances written next to each
//! check; this test only builds, runs and reports it.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The static library of this crate built by `cargo test` sits next to the integration-test
/// binaries (target/<profile>/deps); it carries no hash in its name.
fn static_library() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    let deps = exe.parent().expect("deps directory");
    let lib = deps.join(if cfg!(windows) {
        "clr_contact_capi.lib"
    } else {
        "libclr_contact_capi.a"
    });
    assert!(
        lib.exists(),
        "static library not found at {}; it is built with the crate-type staticlib of \
         clr-contact-capi",
        lib.display()
    );
    lib
}

#[test]
fn c_program_checks_contact_laws_section_7() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let exe = out_dir.join("test_capi");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_string());
    let mut cmd = Command::new(&cc);
    cmd.arg("-std=c99")
        .arg("-Wall")
        .arg("-Wextra")
        .arg("-Werror")
        .arg(format!(
            "-DCLR_EXPECTED_VERSION=\"{}\"",
            env!("CARGO_PKG_VERSION")
        ))
        .arg("-I")
        .arg(dir.join("include"))
        .arg(dir.join("tests/c/test_capi.c"))
        .arg(static_library())
        .arg("-o")
        .arg(&exe);
    // System libraries the Rust standard library needs in a static link
    // (`rustc --print native-static-libs`).
    for lib in [
        "-lgcc_s",
        "-lutil",
        "-lrt",
        "-lpthread",
        "-lm",
        "-ldl",
        "-lc",
    ] {
        cmd.arg(lib);
    }
    let build = cmd
        .output()
        .unwrap_or_else(|e| panic!("cannot run the C compiler `{cc}`: {e}"));
    assert!(
        build.status.success(),
        "compiling the C test failed:\n{}{}",
        String::from_utf8_lossy(&build.stdout),
        String::from_utf8_lossy(&build.stderr)
    );
    let run = Command::new(&exe).output().expect("run the C test");
    let stdout = String::from_utf8_lossy(&run.stdout);
    println!("{stdout}");
    assert!(
        run.status.success(),
        "the C test failed:\n{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let summary = stdout.lines().last().unwrap_or_default();
    assert!(
        summary.ends_with(" 0 failed") && !summary.starts_with("0 passed"),
        "unexpected summary `{summary}`"
    );
}
