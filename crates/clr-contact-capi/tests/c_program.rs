//! Compiles `tests/c/test_capi.c` with the machine's C compiler (`cc`, or `$CC`), links it
//! against the static library built for this test run, runs it and requires every check to pass.
//! The C program compares against contact-laws.md §7 with the tolerances written next to each
//! check; this test builds, runs and reports it, and passes it (as `-D` defines, like the
//! version) one multipoint case with the values clr-contact computes for it directly
//! ([`multipoint_case`]).

use std::path::{Path, PathBuf};
use std::process::Command;

use clr_contact::{ContactClass, FrictionLaw, MultipointDetector};

#[path = "support/multipoint_case.rs"]
mod multipoint_case;
use multipoint_case::{
    body_values, evaluate, hertz_ln, impact_velocities, point_values, straight_case,
    straight_guide, straight_slider, HERTZ_LN, STRAIGHT_JOINT,
};

/// A C initializer `{a, b, …}` of doubles printed to round trip exactly (Rust's shortest
/// representation, which C's strtod reads back to the same double).
fn c_array(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
    format!("{{{}}}", items.join(", "))
}

/// The multipoint case of `multipoint_rust()` in test_capi.c and its expected values, computed
/// here with clr-contact's `StraightGuide` and `MultipointDetector` (not through the C API; the
/// case and the reference evaluation are those of the unit tests, `support/multipoint_case.rs`),
/// as `-D` defines:
///
/// - `CLR_MP_JOINT`: guide length (m), gap_on_left, slider L, h (m), guide origin x, y (m) and
///   angle (rad) on body i, slider centre x, y (m) and angle (rad) on body j, N, M;
/// - `CLR_MP_LAWS`: Hertz K (N/m^1.5), c_e of the Lankarani–Nikravesh damping, Coulomb μ and
///   v_reg (m/s);
/// - `CLR_MP_GUIDE`, `CLR_MP_SLIDER`: body states (x, y, θ, ẋ, ẏ, ω);
/// - `CLR_MP_IMPACT`: δ̇⁻ (m/s) per point id;
/// - `CLR_MP_EXPECTED`: class, area face, active points, contact length, then the generalized
///   forces on guide and slider (f_x, f_y, m);
/// - `CLR_MP_POINTS`: per active point id, source, face, index, arc, δ, n_x, n_y, slider x, y,
///   guide x, y, v_N, v_T, tributary length, F_N, F_T (17 values).
///
/// The slider (0.1 m x 0.02 m) lies 0.2 m down a straight guide on a moving, rotated body,
/// tilted 0.4 mrad against it with its centre 15 µm into it: a line contact of its rear edge
/// (corner 0 and three bottom-face points), with friction, sliding and spinning.
fn multipoint_case() -> Vec<String> {
    let (n_face, m_samples) = (3, 5);
    let mut joint = STRAIGHT_JOINT.to_vec();
    joint.extend([n_face as f64, m_samples as f64]);
    let laws = [HERTZ_LN[0], HERTZ_LN[1], 0.1, 1e-3];
    let (guide, slider) = straight_case(0.2, 15e-6, 4e-4);
    let mut det = MultipointDetector::new(straight_slider(), n_face, m_samples).expect("detector");
    let impact = impact_velocities(det.point_count());
    let friction = FrictionLaw::coulomb(laws[2], laws[3]).expect("friction law");
    let surface = straight_guide(guide);
    let r = evaluate(
        &mut det,
        &surface,
        (&guide, &slider),
        (&hertz_ln(), &friction),
        &impact,
    );
    let ContactClass::Line { length } = r.class else {
        panic!(
            "the C multipoint case must be a line contact, got {:?}",
            r.class
        )
    };
    assert_eq!(det.points().len(), 4, "the C multipoint case has 4 points");
    let mut expected = vec![1.0, -1.0, det.points().len() as f64, length];
    expected.extend(r.guide.as_array());
    expected.extend(r.slider.as_array());
    let points = det.points().iter().zip(&r.forces);
    let points = points.flat_map(|(p, &(f_n, f_t))| point_values(p, f_n, f_t));
    [
        ("CLR_MP_JOINT", joint),
        ("CLR_MP_LAWS", laws.to_vec()),
        ("CLR_MP_GUIDE", body_values(&guide).to_vec()),
        ("CLR_MP_SLIDER", body_values(&slider).to_vec()),
        ("CLR_MP_IMPACT", impact),
        ("CLR_MP_EXPECTED", expected),
        ("CLR_MP_POINTS", points.collect()),
    ]
    .into_iter()
    .map(|(name, values)| format!("-D{name}={}", c_array(&values)))
    .collect()
}

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
        .args(multipoint_case())
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
