//! The committed C header `include/clr_contact.h` must be what cbindgen generates from the
//! current source with `cbindgen.toml`. Run with `CLR_BLESS=1` to rewrite it after an API change.
//!
//! Why a committed header checked by a test rather than a build.rs: a build script that writes
//! into the source tree breaks read-only checkouts and packaging, and would make every build of
//! the library (and of the Python package that depends on it) parse the crate with cbindgen; the
//! committed header is what C users read, and this test keeps it exact.

use std::path::Path;

#[test]
fn committed_header_is_up_to_date() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).expect("UTF-8 header");
    let path = dir.join("include/clr_contact.h");
    if std::env::var_os("CLR_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write the header");
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "include/clr_contact.h is stale: regenerate it with \
         `CLR_BLESS=1 cargo test -p clr-contact-capi --test header` and commit it"
    );
}
