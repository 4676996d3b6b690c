//! `cargo xtask verify`: every verification case of the workspace, grouped by crate.

pub mod beam;
pub mod contact;
mod contact_geometry;
/// The journal-in-bearing configurations shared with the clr-contact tests (spatial_journal,
/// wear_spatial), loaded once.
#[path = "../../../crates/clr-contact/tests/support/journal_setup.rs"]
mod journal_setup;
pub mod lubrication;
mod lubrication_mbd;
mod lubrication_spatial;
mod maps;
mod mbd;
mod mbd_jacobian;
mod mbd_tolerance;
pub mod models;
pub mod models_dual_guide;
mod models_dual_guide_map;
pub mod models_flap_flex;
mod models_flap_map;
pub mod models_flap_misalignment;
mod models_guide_map;
pub mod ode;
mod shapes;
pub(crate) mod spatial;
mod spatial_jacobian;
mod spatial_journal;
mod spatial_ref;
mod spatial_shapes;
mod spatial_slider_crank;
mod wear;
pub mod wear_spatial;

use std::process::ExitCode;
use std::time::Instant;

use crate::report::{self, Case};

/// A group of cases: its id prefix and the function computing them. The function receives the
/// requested prefixes so that it can skip expensive cases nobody asked for.
struct Group {
    name: &'static str,
    run: fn(&Filter) -> Vec<Case>,
}

/// Which case ids were requested (`cargo xtask verify ode.hires contact`).
pub struct Filter {
    prefixes: Vec<String>,
}

impl Filter {
    /// True when a case with this id (or any case under this id prefix) was requested.
    pub fn wants(&self, id: &str) -> bool {
        self.prefixes.is_empty()
            || self
                .prefixes
                .iter()
                .any(|p| id.starts_with(p.as_str()) || p.starts_with(id))
    }
}

const GROUPS: &[Group] = &[
    Group {
        name: "ode",
        run: ode::cases,
    },
    Group {
        name: "contact",
        run: contact::cases,
    },
    Group {
        name: "contact",
        run: contact_geometry::cases,
    },
    Group {
        name: "contact",
        run: shapes::cases,
    },
    Group {
        name: "lubrication",
        run: lubrication::cases,
    },
    Group {
        name: "lubrication",
        run: lubrication_mbd::cases,
    },
    Group {
        name: "lubrication.spatial",
        run: lubrication_spatial::cases,
    },
    Group {
        name: "beam",
        run: beam::cases,
    },
    Group {
        name: "mbd",
        run: mbd::cases,
    },
    Group {
        name: "mbd.jacobian",
        run: mbd_jacobian::cases,
    },
    Group {
        name: "mbd.tolerance",
        run: mbd_tolerance::cases,
    },
    Group {
        name: "mbd.spatial",
        run: spatial::mbd_cases,
    },
    Group {
        name: "mbd.jacobian",
        run: spatial_jacobian::cases,
    },
    Group {
        name: "mbd.spatial",
        run: spatial_slider_crank::cases,
    },
    Group {
        name: "contact.spatial",
        run: spatial::contact_cases,
    },
    Group {
        name: "contact.spatial.revolute",
        run: spatial_journal::cases,
    },
    Group {
        name: "contact.spatial.shapes",
        run: spatial_shapes::cases,
    },
    Group {
        name: "models",
        run: models::cases,
    },
    Group {
        name: "models",
        run: models_flap_flex::cases,
    },
    Group {
        name: "models.flap_misalignment",
        run: models_flap_misalignment::cases,
    },
    Group {
        name: "models",
        run: models_dual_guide::cases,
    },
    Group {
        name: "models",
        run: models_guide_map::cases,
    },
    Group {
        name: "models",
        run: models_dual_guide_map::cases,
    },
    Group {
        name: "models",
        run: models_flap_map::cases,
    },
    Group {
        name: "wear",
        run: wear::cases,
    },
    Group {
        name: "wear.spatial",
        run: wear_spatial::cases,
    },
];

pub fn run(args: &[String]) -> ExitCode {
    let filter = Filter {
        prefixes: args.to_vec(),
    };
    let start = Instant::now();
    let mut cases = Vec::new();
    for g in GROUPS.iter().filter(|g| filter.wants(g.name)) {
        println!("== {} ==", g.name);
        for c in (g.run)(&filter) {
            if filter.prefixes.is_empty()
                || filter.prefixes.iter().any(|p| c.id.starts_with(p.as_str()))
            {
                report::print_case(&c);
                cases.push(c);
            }
        }
    }
    let wall_s = start.elapsed().as_secs_f64();
    let dir = crate::target_dir().join("verify");
    if let Err(e) = report::write(&dir, &cases, wall_s) {
        eprintln!("cannot write the report in {}: {e}", dir.display());
        return ExitCode::FAILURE;
    }
    let gaps = cases.iter().filter(|c| !c.pass && c.known_gap).count();
    let failed = cases.iter().filter(|c| !c.pass && !c.known_gap).count();
    println!(
        "\n{} cases, {} passed, {} failed, {} known gaps, {:.1} s; report in {}",
        cases.len(),
        cases.len() - failed - gaps,
        failed,
        gaps,
        wall_s,
        dir.join("report.md").display()
    );
    if cases.is_empty() {
        eprintln!("no case matches {:?}", filter.prefixes);
        return ExitCode::from(2);
    }
    if failed > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
