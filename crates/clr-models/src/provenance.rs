//! What a result was computed from, so that results of different models or program versions
//! are not mixed (`clr merge` of sweep shards, the checkpoints of finding maps): the clr
//! version and a hash of the resolved model.
//!
//! The hash is the 64-bit FNV-1a of the model's canonical JSON text: compact, object keys in
//! sorted order (serde_json's map), numbers in their shortest round-trip form. It changes with
//! any value of the model and is the same on every machine; it is not a cryptographic hash (it
//! tells runs apart, it does not authenticate them).

/// The clr version that computed a result (the workspace's `version`).
pub const CLR_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The 64-bit FNV-1a hash of `bytes` (offset basis 0xcbf29ce484222325, prime 0x100000001b3).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The hash of a resolved model given as JSON: `fnv1a64:` and 16 hex digits of
/// [`fnv1a64`] of its canonical text (see the module documentation).
pub fn model_hash(model: &serde_json::Value) -> String {
    let text = serde_json::to_string(model).unwrap_or_default();
    format!("fnv1a64:{:016x}", fnv1a64(text.as_bytes()))
}

/// What a shard's files record about how it was computed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Recorded {
    /// [`CLR_VERSION`] of the clr that computed it.
    pub clr_version: String,
    /// [`model_hash`] of the model it ran.
    pub model_hash: String,
}

/// One shard given to a merge.
#[derive(Debug, Clone)]
pub struct Shard {
    /// Its folder, as given.
    pub folder: String,
    /// Its `I/N`.
    pub spec: String,
    /// The command that re-runs it (shown in the refusal).
    pub rerun: String,
    /// Its provenance; `None` for a shard written before clr recorded it.
    pub recorded: Option<Recorded>,
}

/// A shard whose model hash or clr version differs from the first shard's.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "{shard}: {what} {theirs} differs from {first}'s {ours}: the two shards were computed from \
     {meaning}, so their points do not belong to one {kind}; re-run shard {spec} (`{rerun}`) \
     with the {remedy} the other shards used, then merge again"
)]
pub struct Difference {
    /// Folder of the differing shard.
    pub shard: String,
    /// Folder of the first shard (the reference).
    pub first: String,
    /// `model_hash` or `clr_version`.
    pub what: &'static str,
    /// The differing shard's value.
    pub theirs: String,
    /// The first shard's value.
    pub ours: String,
    /// What the difference means.
    pub meaning: &'static str,
    /// What was merged (`sweep`, `finding map`).
    pub kind: &'static str,
    /// The shard's `I/N`.
    pub spec: String,
    /// The command that re-runs it.
    pub rerun: String,
    /// What to keep the same when re-running it.
    pub remedy: &'static str,
}

/// Why shards cannot be merged: something refutes, or nothing shows, that they were computed
/// from one model by one clr version.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ProvenanceError {
    /// A shard's model hash or clr version differs from the first shard's.
    #[error(transparent)]
    Differs(Box<Difference>),
    /// Shards whose files record no provenance (written before clr recorded it).
    #[error(
        "{shards}: no model_hash or clr_version recorded (written by a clr that did not record \
         them), so nothing shows that these shards ran the same model as the others; re-run \
         them with this clr, or give --allow-unverified to merge them anyway (they are then \
         named in a warning and in the merged output)"
    )]
    Unverified {
        /// The folders without provenance, comma-separated.
        shards: String,
    },
}

/// Check that `shards` of one `kind` (`sweep`, `finding map`) were computed by one clr
/// version from one model, each compared with the first shard that records its provenance.
/// Returns the folders without provenance, accepted only with `allow_unverified`.
///
/// # Errors
/// [`ProvenanceError::Differs`] for the first shard that differs, naming it;
/// [`ProvenanceError::Unverified`] for shards without provenance unless `allow_unverified`.
pub fn check_shards(
    shards: &[Shard],
    kind: &'static str,
    allow_unverified: bool,
) -> Result<Vec<String>, ProvenanceError> {
    let unverified: Vec<String> = shards
        .iter()
        .filter(|s| s.recorded.is_none())
        .map(|s| s.folder.clone())
        .collect();
    if !unverified.is_empty() && !allow_unverified {
        return Err(ProvenanceError::Unverified {
            shards: unverified.join(", "),
        });
    }
    let mut verified = shards
        .iter()
        .filter_map(|s| s.recorded.as_ref().map(|r| (s, r)));
    let Some((s0, r0)) = verified.next() else {
        return Ok(unverified);
    };
    for (s, r) in verified {
        let differs = |what, theirs: &str, ours: &str, meaning, remedy| {
            ProvenanceError::Differs(Box::new(Difference {
                shard: s.folder.clone(),
                first: s0.folder.clone(),
                what,
                theirs: theirs.to_string(),
                ours: ours.to_string(),
                meaning,
                kind,
                spec: s.spec.clone(),
                rerun: s.rerun.clone(),
                remedy,
            }))
        };
        if r.clr_version != r0.clr_version {
            return Err(differs(
                "clr_version",
                &r.clr_version,
                &r0.clr_version,
                "different clr versions",
                "clr version",
            ));
        }
        if r.model_hash != r0.model_hash {
            return Err(differs(
                "model_hash",
                &r.model_hash,
                &r0.model_hash,
                "different models (the model file, a --set value or an option changed between \
                 them)",
                "model file and options",
            ));
        }
    }
    Ok(unverified)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The published FNV-1a 64 test vectors ("" and "a"), so the hash is the documented one.
    #[test]
    fn fnv1a64_gives_the_published_values() {
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
    }

    /// Key order does not change the hash (maps are sorted); any value does.
    #[test]
    fn the_hash_follows_the_content_not_the_key_order() {
        let a: serde_json::Value = serde_json::from_str(r#"{"m": 1.0, "c": [0.5]}"#).unwrap();
        let b: serde_json::Value = serde_json::from_str(r#"{"c": [0.5], "m": 1.0}"#).unwrap();
        let c: serde_json::Value = serde_json::from_str(r#"{"c": [0.5], "m": 1.5}"#).unwrap();
        assert_eq!(model_hash(&a), model_hash(&b));
        assert_ne!(model_hash(&a), model_hash(&c));
        assert!(model_hash(&a).starts_with("fnv1a64:") && model_hash(&a).len() == 24);
    }

    fn shard(folder: &str, recorded: Option<(&str, &str)>) -> Shard {
        Shard {
            folder: folder.into(),
            spec: "1/2".into(),
            rerun: format!("clr sweep m.toml --shard 1/2 --out {folder}"),
            recorded: recorded.map(|(v, h)| Recorded {
                clr_version: v.into(),
                model_hash: h.into(),
            }),
        }
    }

    /// The first shard that differs is named with both values; a version difference is
    /// reported as such; shards without provenance are refused unless allowed, then returned.
    #[test]
    fn shards_of_different_provenance_are_refused_by_name() {
        let a = shard("a", Some(("0.1.0", "fnv1a64:1")));
        let b = shard("b", Some(("0.1.0", "fnv1a64:2")));
        let c = shard("c", Some(("0.2.0", "fnv1a64:1")));
        let old = shard("old", None);
        assert_eq!(
            check_shards(&[a.clone(), a.clone()], "sweep", false),
            Ok(vec![])
        );
        let e = check_shards(&[a.clone(), b], "sweep", false)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("b: model_hash fnv1a64:2 differs from a's fnv1a64:1"),
            "{e}"
        );
        assert!(
            e.contains("re-run shard 1/2 (`clr sweep m.toml --shard 1/2 --out b`)"),
            "{e}"
        );
        let e = check_shards(&[a.clone(), c], "sweep", false)
            .unwrap_err()
            .to_string();
        assert!(e.contains("clr_version 0.2.0 differs"), "{e}");
        let e = check_shards(&[a.clone(), old.clone()], "sweep", false).unwrap_err();
        assert_eq!(
            e,
            ProvenanceError::Unverified {
                shards: "old".into()
            }
        );
        assert_eq!(
            check_shards(&[old, a], "sweep", true),
            Ok(vec!["old".to_string()])
        );
    }
}
