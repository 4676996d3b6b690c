//! The exported `extern "C"` functions and the C-visible types.
//!
//! Every fallible function returns a [`ClrStatus`] and writes its result through an output
//! pointer only on success. Handles are created by `clr_*_new`/`clr_normal_law_preset` and
//! released by the matching `clr_*_free` (NULL is accepted and ignored). Handles are immutable
//! after construction except through `clr_normal_law_set_min_impact_velocity`, so one handle can be
//! evaluated from several threads at once as long as nobody frees or modifies it meanwhile. The
//! multipoint joint ([`crate::multipoint`]) is the exception: its evaluation updates the warm
//! starts and the point buffers inside the handle, so it needs one handle per thread.

use std::ffi::{c_char, CStr};

use clr_contact::body::BodyState;
use clr_contact::elastic::Material;
use clr_contact::restitution::effective_restitution;
use clr_contact::revolute::JointForces;
use clr_contact::translational::GuideSide;
use clr_contact::{
    Configuration, FrictionLaw, JournalBearing, LuGre, NormalLaw, RevoluteClearance, SliderShape,
    TranslationalClearance,
};

use crate::error::{finite, guard, last_error_ptr, CapiError, ClrStatus};
use crate::spec::{damping_from_code, ElasticKind, FrictionKind, Kind};

/// Code of an elastic part for `clr_normal_law_new` (one of the `CLR_ELASTIC_*` constants).
pub type ClrElasticKind = u32;
/// Hertz F = K δ^1.5 with a given K. Parameters: K (N/m^1.5).
pub const CLR_ELASTIC_HERTZ: ClrElasticKind = 0;
/// Power law F = K δ^n. Parameters: K (N/m^n), n (-).
pub const CLR_ELASTIC_POWER: ClrElasticKind = 1;
/// Linear spring F = k δ. Parameters: k (N/m).
pub const CLR_ELASTIC_LINEAR: ClrElasticKind = 2;
/// Hertz, two convex spheres. Parameters: E1 (Pa), nu1, R1 (m), E2 (Pa), nu2, R2 (m).
pub const CLR_ELASTIC_HERTZ_SPHERE_SPHERE: ClrElasticKind = 3;
/// Hertz, sphere on a plane. Parameters: E_sphere (Pa), nu_sphere, R (m), E_plane (Pa), nu_plane.
pub const CLR_ELASTIC_HERTZ_SPHERE_PLANE: ClrElasticKind = 4;
/// Hertz, journal in a bearing (Flores et al. 2004). Parameters: E_bearing (Pa), nu_bearing,
/// R_bearing (m), E_journal (Pa), nu_journal, R_journal (m).
pub const CLR_ELASTIC_HERTZ_INTERNAL_CYLINDER: ClrElasticKind = 5;
/// Liu, Zhang & Yang (2007) conformal cylinder. Parameters: E* (Pa), clearance (m), length (m).
pub const CLR_ELASTIC_LIU: ClrElasticKind = 6;
/// Bai & Zhao (2012) hybrid stiffness, SI numbers. Parameters: E* (Pa), clearance (m).
pub const CLR_ELASTIC_BAI_ZHAO: ClrElasticKind = 7;
/// Pereira, Ramalho & Ambrósio (2011), internal. Parameters: E* (Pa), clearance (m), length (m).
pub const CLR_ELASTIC_PEREIRA_INTERNAL: ClrElasticKind = 8;
/// Pereira, Ramalho & Ambrósio (2011), external. Parameters: E* (Pa), R1 (m), R2 (m), length (m).
pub const CLR_ELASTIC_PEREIRA_EXTERNAL: ClrElasticKind = 9;
/// Johnson's implicit line contact. Parameters: E* (Pa), clearance (m), length (m).
pub const CLR_ELASTIC_JOHNSON: ClrElasticKind = 10;

/// Code of a damping factor χ(c_e) (one of the `CLR_DAMPING_*` constants).
pub type ClrDampingKind = u32;
/// No damping, χ = 0 (purely elastic).
pub const CLR_DAMPING_NONE: ClrDampingKind = 0;
/// Hunt & Crossley (1975): χ = 3(1 − c_e)/2.
pub const CLR_DAMPING_HUNT_CROSSLEY: ClrDampingKind = 1;
/// Lankarani & Nikravesh (1990): χ = 3(1 − c_e²)/4.
pub const CLR_DAMPING_LANKARANI_NIKRAVESH: ClrDampingKind = 2;
/// Flores et al. (2011): χ = 8(1 − c_e)/(5 c_e).
pub const CLR_DAMPING_FLORES: ClrDampingKind = 3;
/// Gonthier et al. (2004): χ = (1 − c_e²)/c_e.
pub const CLR_DAMPING_GONTHIER: ClrDampingKind = 4;
/// Zhiying & Qishao (2006): χ = 3(1 − c_e²) e^{2(1 − c_e)}/4.
pub const CLR_DAMPING_ZHIYING_QISHAO: ClrDampingKind = 5;
/// Hu & Guo (2015): χ = 3(1 − c_e)/(2 c_e).
pub const CLR_DAMPING_HU_GUO: ClrDampingKind = 6;
/// Gharib & Hurmuzlu (2012): χ = (1 − c_e)/c_e.
pub const CLR_DAMPING_GHARIB_HURMUZLU: ClrDampingKind = 7;
/// Herbert & McWhannell (1977): χ = 6(1 − c_e)/((2c_e − 1)² + 3).
pub const CLR_DAMPING_HERBERT_MCWHANNELL: ClrDampingKind = 8;
/// Lee & Wang (1983): χ = 3(1 − c_e)/4.
pub const CLR_DAMPING_LEE_WANG: ClrDampingKind = 9;
/// Restitution-exact χ, root of (1 + c_e)χ = ln[(1 + χ)/(1 − χ c_e)].
pub const CLR_DAMPING_EXACT: ClrDampingKind = 10;

/// Code of a friction law for `clr_friction_law_new` (one of the `CLR_FRICTION_*` constants).
pub type ClrFrictionKind = u32;
/// Coulomb, regularized linearly below v_reg. Parameters: mu, v_reg (m/s).
pub const CLR_FRICTION_COULOMB: ClrFrictionKind = 0;
/// Ambrósio's modified Coulomb law. Parameters: mu, v0 (m/s), v1 (m/s).
pub const CLR_FRICTION_AMBROSIO: ClrFrictionKind = 1;
/// Threlfall (1978). Parameters: mu, v0 (m/s).
pub const CLR_FRICTION_THRELFALL: ClrFrictionKind = 2;
/// Bai & Zhao / ADAMS-STEP Stribeck-type law. Parameters: mu_s, mu_d, v_s (m/s), v_d (m/s).
pub const CLR_FRICTION_STRIBECK: ClrFrictionKind = 3;

/// Opaque handle of a normal-force law F_N = F_e(δ)(1 + χ δ̇/δ̇⁻).
pub struct ClrNormalLaw(pub(crate) NormalLaw);

/// Opaque handle of a stateless friction law F_T = μ(v_T) F_N.
pub struct ClrFrictionLaw(pub(crate) FrictionLaw);

/// Opaque handle of a planar revolute clearance joint (journal in bearing).
pub struct ClrRevoluteJoint(pub(crate) RevoluteClearance);

/// Geometry and materials of a journal in a bearing, for `clr_normal_law_preset`. SI units.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClrJournalBearing {
    /// Young's modulus of the bearing, Pa.
    pub bearing_youngs_modulus: f64,
    /// Poisson ratio of the bearing, -.
    pub bearing_poisson_ratio: f64,
    /// Young's modulus of the journal, Pa.
    pub journal_youngs_modulus: f64,
    /// Poisson ratio of the journal, -.
    pub journal_poisson_ratio: f64,
    /// Bearing (hole) radius R_i, m.
    pub bearing_radius: f64,
    /// Journal (pin) radius R_j < R_i, m.
    pub journal_radius: f64,
    /// Axial length L, m.
    pub length: f64,
}

/// State of a planar rigid body: reference point, angle and their rates. SI units.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClrBodyState {
    /// x of the reference point, m.
    pub x: f64,
    /// y of the reference point, m.
    pub y: f64,
    /// Angle θ of the body frame, rad, counter-clockwise.
    pub theta: f64,
    /// ẋ, m/s.
    pub vx: f64,
    /// ẏ, m/s.
    pub vy: f64,
    /// ω = θ̇, rad/s.
    pub omega: f64,
}

/// A planar generalized force on a body about its reference point.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClrGeneralizedForce {
    /// Force x component, N.
    pub fx: f64,
    /// Force y component, N.
    pub fy: f64,
    /// Moment about the body's reference point, N·m, counter-clockwise positive.
    pub moment: f64,
}

/// Result of `clr_revolute_joint_forces`. All zero forces when not in contact (δ ≤ 0).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClrRevoluteForces {
    /// Penetration δ = e − c, m (> 0 in contact).
    pub penetration: f64,
    /// Unit normal n (bearing centre → journal centre), x component.
    pub normal_x: f64,
    /// Unit normal n, y component.
    pub normal_y: f64,
    /// Relative normal velocity v_N = δ̇, m/s (> 0 approaching).
    pub normal_velocity: f64,
    /// Relative tangential velocity v_T, m/s.
    pub tangential_velocity: f64,
    /// Normal force F_N ≥ 0 applied, N.
    pub normal_force: f64,
    /// Friction force F_T on the journal along t = k × n, N.
    pub tangential_force: f64,
    /// Generalized force on the bearing body (i).
    pub bearing: ClrGeneralizedForce,
    /// Generalized force on the journal body (j).
    pub journal: ClrGeneralizedForce,
}

/// Opaque handle of a LuGre friction model (Canudas de Wit et al. 1995), whose bristle deflection
/// z (m) is a state the caller integrates.
pub struct ClrLuGre(pub(crate) LuGre);

/// Opaque handle of a planar translational clearance joint (rectangular slider in a guide).
pub struct ClrTranslationalJoint(pub(crate) TranslationalClearance);

/// Configuration of a translational clearance joint (Flores et al. 2008, Fig. 3), one of the
/// `CLR_CONFIGURATION_*` constants.
pub type ClrConfiguration = u32;
/// No corner touches a guide surface.
pub const CLR_CONFIGURATION_FREE_FLIGHT: ClrConfiguration = 0;
/// Exactly one corner penetrates a guide surface.
pub const CLR_CONFIGURATION_ONE_CORNER: ClrConfiguration = 1;
/// Two corners penetrate the same guide surface.
pub const CLR_CONFIGURATION_TWO_CORNERS_ONE_SURFACE: ClrConfiguration = 2;
/// Two corners penetrate opposite guide surfaces (slider jammed diagonally).
pub const CLR_CONFIGURATION_TWO_CORNERS_OPPOSITE_SURFACES: ClrConfiguration = 3;
/// Three or four corners penetrate (penetration comparable to the clearance, outside the validity
/// of the point-contact model; the contacts are still reported).
pub const CLR_CONFIGURATION_MORE_CORNERS: ClrConfiguration = 4;

/// Result of `clr_lugre_evaluate`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClrLuGreOutput {
    /// Bristle rate ż = v_T − σ₀|v_T|z/g(v_T), m/s (integrate it to advance z).
    pub z_dot: f64,
    /// Friction coefficient μ = σ₀z + σ₁ż + σ₂v_T, –, positive along the slip.
    pub coefficient: f64,
    /// Friction force F_T = −μ F_N along the tangent, N; 0 for F_N ≤ 0.
    pub friction_force: f64,
}

/// Contact of one slider corner in `ClrTranslationalForces`. All fields are 0 when the corner does
/// not penetrate a guide surface (`active` = 0).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClrCornerContact {
    /// 1 when this corner penetrates a guide surface, 0 otherwise.
    pub active: i32,
    /// Surface penetrated: +1 the upper one (y = +W/2 of the guide frame), −1 the lower one
    /// (y = −W/2), 0 none.
    pub side: i32,
    /// Penetration δ beyond the surface, m (> 0 when active).
    pub penetration: f64,
    /// Unit normal n (from the channel into the penetrated wall), x component.
    pub normal_x: f64,
    /// Unit normal n, y component.
    pub normal_y: f64,
    /// Relative normal velocity v_N = δ̇, m/s (> 0 approaching).
    pub normal_velocity: f64,
    /// Relative tangential velocity v_T along t = k × n, m/s.
    pub tangential_velocity: f64,
    /// Normal force F_N ≥ 0 at this corner, N.
    pub normal_force: f64,
    /// Friction force F_T on the slider along t at this corner, N.
    pub tangential_force: f64,
}

/// Result of `clr_translational_joint_forces`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClrTranslationalForces {
    /// Configuration of the corners (`CLR_CONFIGURATION_*`).
    pub configuration: ClrConfiguration,
    /// Per corner, numbered counter-clockwise from (−L/2, −h/2) of the slider frame.
    pub corners: [ClrCornerContact; 4],
    /// Generalized force on the guide body (i) about its reference point.
    pub guide: ClrGeneralizedForce,
    /// Generalized force on the slider body (j) about its reference point.
    pub slider: ClrGeneralizedForce,
}

/// Borrow a handle or report a NULL pointer.
///
/// # Safety
/// `p` is NULL or points to a live value.
pub(crate) unsafe fn borrow<'a, T>(name: &'static str, p: *const T) -> Result<&'a T, CapiError> {
    p.as_ref().ok_or(CapiError::Null(name))
}

/// Borrow a handle mutably or report a NULL pointer.
///
/// # Safety
/// `p` is NULL or points to a live value that nothing else uses during the borrow.
pub(crate) unsafe fn borrow_mut<'a, T>(
    name: &'static str,
    p: *mut T,
) -> Result<&'a mut T, CapiError> {
    p.as_mut().ok_or(CapiError::Null(name))
}

/// Require an input pointer that is not NULL.
pub(crate) fn non_null<T>(name: &'static str, p: *const T) -> Result<*const T, CapiError> {
    if p.is_null() {
        Err(CapiError::Null(name))
    } else {
        Ok(p)
    }
}

/// Check an output pointer before any work, so that nothing is written on failure.
pub(crate) fn out_ptr<T>(name: &'static str, p: *mut T) -> Result<*mut T, CapiError> {
    non_null(name, p).map(<*const T>::cast_mut)
}

/// A variable-length result into the caller's buffer `buf` of room `capacity` (checked non-NULL
/// by the caller when `capacity` > 0): `*count` receives `needed`; when `capacity` < `needed`
/// nothing is copied and the error is [`CapiError::BufferTooSmall`] naming `name`; otherwise
/// `fill` writes the `needed` values from `buf` on.
///
/// # Safety
/// `buf` points to `capacity` writable values; `count` is writable.
pub(crate) unsafe fn fill_buffer<T>(
    name: &'static str,
    buf: *mut T,
    capacity: usize,
    count: *mut usize,
    needed: usize,
    fill: impl FnOnce(*mut T),
) -> Result<(), CapiError> {
    count.write(needed);
    if needed > capacity {
        return Err(CapiError::BufferTooSmall {
            name,
            needed,
            capacity,
        });
    }
    fill(buf);
    Ok(())
}

/// The body of a C function with one output `out`: at the boundary ([`guard`]), `out` is checked
/// for NULL first, then `f` computes the value, which is written to `*out` only on success.
///
/// # Safety
/// `out` is NULL or writable.
pub(crate) unsafe fn write_out<T>(
    out: *mut T,
    f: impl FnOnce() -> Result<T, CapiError>,
) -> ClrStatus {
    guard(|| {
        let out = out_ptr("out", out)?;
        out.write(f()?);
        Ok(())
    })
}

/// [`write_out`] of a new heap handle holding what `f` builds (released by [`free_handle`]).
///
/// # Safety
/// `out` is NULL or writable.
pub(crate) unsafe fn new_handle<H>(
    out: *mut *mut H,
    f: impl FnOnce() -> Result<H, CapiError>,
) -> ClrStatus {
    write_out(out, || f().map(|handle| Box::into_raw(Box::new(handle))))
}

/// Release a handle of [`new_handle`]; NULL is ignored.
///
/// # Safety
/// `p` is NULL or a handle of [`new_handle`] not freed yet.
pub(crate) unsafe fn free_handle<H>(p: *mut H) {
    if !p.is_null() {
        drop(Box::from_raw(p));
    }
}

/// # Safety
/// `p` is NULL with `n == 0`, or points to `n` readable doubles.
unsafe fn params<'a>(p: *const f64, n: usize) -> Result<&'a [f64], CapiError> {
    if n == 0 {
        Ok(&[])
    } else {
        Ok(std::slice::from_raw_parts(non_null("params", p)?, n))
    }
}

pub(crate) fn body_state(name: &'static str, s: &ClrBodyState) -> Result<BodyState, CapiError> {
    for v in [s.x, s.y, s.theta, s.vx, s.vy, s.omega] {
        finite(name, v)?;
    }
    Ok(BodyState::new(
        [s.x, s.y].into(),
        s.theta,
        [s.vx, s.vy].into(),
        s.omega,
    ))
}

/// Names of the body-state arguments of a joint evaluation, for body i then body j: the
/// argument (named when NULL) and its state (named when not finite).
pub(crate) type BodyNames = [(&'static str, &'static str); 2];
/// The bodies of a revolute joint.
const BEARING_JOURNAL: BodyNames = [("bearing", "bearing state"), ("journal", "journal state")];
/// The bodies of a translational or multipoint joint.
pub(crate) const GUIDE_SLIDER: BodyNames = [("guide", "guide state"), ("slider", "slider state")];
/// Name of the impact-velocity array argument of the joint evaluations, for messages.
pub(crate) const IMPACT_VELOCITIES: &str = "impact_velocities";

/// The laws and body states of a joint evaluation (`clr_*_joint_forces`), checked.
pub(crate) struct JointInputs<'a> {
    /// The normal-force law.
    pub normal: &'a NormalLaw,
    /// The friction law; None (a NULL handle) for a frictionless joint.
    pub friction: Option<&'a FrictionLaw>,
    /// State of body i (bearing or guide).
    pub i: BodyState,
    /// State of body j (journal or slider).
    pub j: BodyState,
}

impl JointInputs<'_> {
    /// Read the laws, then the states `bodies` of bodies i and j (named by `names`), in this
    /// order: the first NULL pointer or non-finite state is the error.
    ///
    /// # Safety
    /// `normal` is NULL or a live handle; `friction` is NULL or a live handle; the `bodies` are
    /// NULL or point to `ClrBodyState`.
    pub(crate) unsafe fn read(
        normal: *const ClrNormalLaw,
        friction: *const ClrFrictionLaw,
        bodies: [*const ClrBodyState; 2],
        names: BodyNames,
    ) -> Result<Self, CapiError> {
        let normal = &borrow("normal", normal)?.0;
        let friction = friction.as_ref().map(|f| &f.0);
        let [(ni, si), (nj, sj)] = names;
        let i = body_state(si, borrow(ni, bodies[0])?)?;
        let j = body_state(sj, borrow(nj, bodies[1])?)?;
        Ok(Self {
            normal,
            friction,
            i,
            j,
        })
    }
}

pub(crate) fn generalized(g: clr_contact::GeneralizedForce) -> ClrGeneralizedForce {
    ClrGeneralizedForce {
        fx: g.force.x,
        fy: g.force.y,
        moment: g.moment,
    }
}

/// The library version, e.g. "0.1.0" (static string).
#[no_mangle]
pub extern "C" fn clr_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// Message of the last failed call on this thread (UTF-8, NUL-terminated; empty if none failed).
/// The pointer is owned by the library and valid until the next failing call on this thread;
/// copy the text if you need it longer. Never NULL.
#[no_mangle]
pub extern "C" fn clr_last_error_message() -> *const c_char {
    last_error_ptr()
}

/// The journal–bearing test of the flap paper (Wan et al., Machines 10 (2022) 1098): steel
/// (207 GPa, 0.3) on both sides, R_i = 10 mm, R_j = 9.9 mm, L = 15 mm.
#[no_mangle]
pub extern "C" fn clr_journal_bearing_flap_paper_test() -> ClrJournalBearing {
    let jb = JournalBearing::flap_paper_test();
    ClrJournalBearing {
        bearing_youngs_modulus: jb.bearing.youngs_modulus,
        bearing_poisson_ratio: jb.bearing.poisson_ratio,
        journal_youngs_modulus: jb.journal.youngs_modulus,
        journal_poisson_ratio: jb.journal.poisson_ratio,
        bearing_radius: jb.r_bearing,
        journal_radius: jb.r_journal,
        length: jb.length,
    }
}

/// Create a journal–bearing normal law by the flap paper's label (case-insensitive): "Hertz",
/// "LN", "Gonthier", "Bai", "Wang" or "Modified" (see `NormalLaw::preset` in clr-contact for the
/// elastic part and damping factor of each), for the geometry `*geometry` and the input
/// coefficient of restitution c_e ∈ (0, 1]. On success `*out` receives a new handle to free with
/// `clr_normal_law_free`.
///
/// # Safety
/// `name` is NULL or a NUL-terminated string; `geometry` is NULL or points to a
/// `ClrJournalBearing`; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_normal_law_preset(
    name: *const c_char,
    geometry: *const ClrJournalBearing,
    c_e: f64,
    out: *mut *mut ClrNormalLaw,
) -> ClrStatus {
    new_handle(out, || {
        let name = CStr::from_ptr(non_null("name", name)?)
            .to_str()
            .map_err(|_| CapiError::Utf8("name"))?;
        let g = borrow("geometry", geometry)?;
        let jb = JournalBearing {
            bearing: Material {
                youngs_modulus: g.bearing_youngs_modulus,
                poisson_ratio: g.bearing_poisson_ratio,
            },
            journal: Material {
                youngs_modulus: g.journal_youngs_modulus,
                poisson_ratio: g.journal_poisson_ratio,
            },
            r_bearing: g.bearing_radius,
            r_journal: g.journal_radius,
            length: g.length,
        };
        Ok(ClrNormalLaw(NormalLaw::preset(name, &jb, c_e)?))
    })
}

/// Create a normal law from an elastic part (`CLR_ELASTIC_*` with its `n_params` parameters in
/// SI, in the order documented at each constant), a damping factor (`CLR_DAMPING_*`) and the
/// input coefficient of restitution c_e ∈ (0, 1]. On success `*out` receives a new handle to free
/// with `clr_normal_law_free`.
///
/// # Safety
/// `params` points to `n_params` doubles (may be NULL if `n_params` is 0); `out` is NULL or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn clr_normal_law_new(
    elastic: ClrElasticKind,
    params: *const f64,
    n_params: usize,
    damping: ClrDampingKind,
    c_e: f64,
    out: *mut *mut ClrNormalLaw,
) -> ClrStatus {
    new_handle(out, || {
        let p = self::params(params, n_params)?;
        let elastic = ElasticKind::from_code(elastic)?.build(p)?;
        let law = NormalLaw::new(elastic, damping_from_code(damping)?, c_e)?;
        Ok(ClrNormalLaw(law))
    })
}

/// Set the floor of δ̇⁻ (m/s, > 0; default 1e-4): below it the impact velocity is replaced by
/// this value so that a contact starting at rest keeps a finite damping.
///
/// # Safety
/// `law` is NULL or a live handle not used by another thread during the call.
#[no_mangle]
pub unsafe extern "C" fn clr_normal_law_set_min_impact_velocity(
    law: *mut ClrNormalLaw,
    min_impact_velocity: f64,
) -> ClrStatus {
    guard(|| {
        let law = borrow_mut("law", law)?;
        law.0 = law.0.with_min_impact_velocity(min_impact_velocity)?;
        Ok(())
    })
}

/// Normal force F_N (N) for the penetration δ (m), its rate δ̇ (m/s, > 0 approaching) and the
/// rate at contact onset δ̇⁻ (m/s): F_N = max(0, F_e(δ)(1 + χ δ̇/max(δ̇⁻, floor))), 0 for δ ≤ 0.
/// Non-finite inputs are rejected with `CLR_STATUS_NON_FINITE`. Allocates nothing on success.
///
/// # Safety
/// `law` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_normal_law_force(
    law: *const ClrNormalLaw,
    delta: f64,
    delta_dot: f64,
    delta_dot_minus: f64,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || {
        let law = borrow("law", law)?;
        let d = finite("delta (m)", delta)?;
        let dd = finite("delta_dot (m/s)", delta_dot)?;
        let ddm = finite("delta_dot_minus (m/s)", delta_dot_minus)?;
        Ok(law.0.force(d, dd, ddm))
    })
}

/// Elastic part F_e(δ) (N) of the law for the penetration δ (m); 0 for δ ≤ 0.
///
/// # Safety
/// `law` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_normal_law_elastic_force(
    law: *const ClrNormalLaw,
    delta: f64,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || {
        let law = borrow("law", law)?;
        Ok(law.0.elastic_force(finite("delta (m)", delta)?))
    })
}

/// Damping factor χ (–) of the law.
///
/// # Safety
/// `law` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_normal_law_chi(law: *const ClrNormalLaw, out: *mut f64) -> ClrStatus {
    write_out(out, || Ok(borrow("law", law)?.0.chi()))
}

/// Restitution (–) the law produces in a free impact, exact for any elastic part: the root e of
/// (1 + e)χ = ln[(1 + χ)/(1 − χe)] (contact-laws.md §1.3).
///
/// # Safety
/// `law` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_normal_law_effective_restitution(
    law: *const ClrNormalLaw,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || Ok(borrow("law", law)?.0.effective_restitution()))
}

/// Free a normal law. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `law` is NULL or a handle from `clr_normal_law_new`/`clr_normal_law_preset` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_normal_law_free(law: *mut ClrNormalLaw) {
    free_handle(law)
}

/// Damping factor χ (–) of the factor `damping` (`CLR_DAMPING_*`) for the input coefficient of
/// restitution c_e ∈ (0, 1].
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_damping_chi(
    damping: ClrDampingKind,
    c_e: f64,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || Ok(damping_from_code(damping)?.chi(c_e)?))
}

/// Restitution e (–) produced by a multiplicative law with damping factor χ ≥ 0 in a free impact:
/// the root of (1 + e)χ = ln[(1 + χ)/(1 − χe)] (contact-laws.md §1.3).
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_effective_restitution(chi: f64, out: *mut f64) -> ClrStatus {
    write_out(out, || Ok(effective_restitution(chi)?))
}

/// Create a friction law (`CLR_FRICTION_*` with its `n_params` parameters, in the order
/// documented at each constant). On success `*out` receives a new handle to free with
/// `clr_friction_law_free`.
///
/// # Safety
/// `params` points to `n_params` doubles (may be NULL if `n_params` is 0); `out` is NULL or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn clr_friction_law_new(
    kind: ClrFrictionKind,
    params: *const f64,
    n_params: usize,
    out: *mut *mut ClrFrictionLaw,
) -> ClrStatus {
    new_handle(out, || {
        let law = FrictionKind::from_code(kind)?.build(self::params(params, n_params)?)?;
        Ok(ClrFrictionLaw(law))
    })
}

/// Friction force F_T (N) on body j along the tangent, for the slip velocity v_T (m/s) and the
/// normal force F_N (N): F_T = μ(v_T) F_N, opposing v_T; 0 for F_N ≤ 0.
///
/// # Safety
/// `law` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_friction_law_force(
    law: *const ClrFrictionLaw,
    v_t: f64,
    f_n: f64,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || {
        let law = borrow("law", law)?;
        let v = finite("v_t (m/s)", v_t)?;
        let f = finite("f_n (N)", f_n)?;
        Ok(law.0.force(v, f))
    })
}

/// Signed friction coefficient μ(v_T) (–), with μ·v_T ≤ 0, so that F_T = μ F_N.
///
/// # Safety
/// `law` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_friction_law_coefficient(
    law: *const ClrFrictionLaw,
    v_t: f64,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || {
        let law = borrow("law", law)?;
        Ok(law.0.signed_coefficient(finite("v_t (m/s)", v_t)?))
    })
}

/// Free a friction law. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `law` is NULL or a handle from `clr_friction_law_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_friction_law_free(law: *mut ClrFrictionLaw) {
    free_handle(law)
}

/// Create a planar revolute clearance joint: bearing radius R_i and journal radius R_j (m,
/// R_i > R_j > 0), and the local coordinates (m) of the bearing centre on body i and of the
/// journal centre on body j. On success `*out` receives a new handle to free with
/// `clr_revolute_joint_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_revolute_joint_new(
    bearing_radius: f64,
    journal_radius: f64,
    bearing_centre_x: f64,
    bearing_centre_y: f64,
    journal_centre_x: f64,
    journal_centre_y: f64,
    out: *mut *mut ClrRevoluteJoint,
) -> ClrStatus {
    new_handle(out, || {
        let joint = RevoluteClearance::new(
            bearing_radius,
            journal_radius,
            [bearing_centre_x, bearing_centre_y].into(),
            [journal_centre_x, journal_centre_y].into(),
        )?;
        Ok(ClrRevoluteJoint(joint))
    })
}

/// Generalized forces of the clearance joint on both bodies (Flores et al., Comput. Struct. 82
/// (2004) 1359): penetration δ = |r_j^P − r_i^P| − (R_i − R_j), F_N from `normal` with δ̇ = v_N
/// and the impact velocity δ̇⁻ = `impact_velocity` (m/s; the caller keeps it per contact: the
/// v_N at the first evaluation with δ > 0, until separation), F_T from `friction` (NULL:
/// frictionless), force on the journal −F_N n + F_T t at its contact point and the opposite on
/// the bearing, reduced to each body's reference point. Zero forces when δ ≤ 0.
///
/// # Safety
/// `joint`, `normal` are NULL or live handles; `friction` is NULL or a live handle; `bearing`,
/// `journal` are NULL or point to `ClrBodyState`; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_revolute_joint_forces(
    joint: *const ClrRevoluteJoint,
    normal: *const ClrNormalLaw,
    friction: *const ClrFrictionLaw,
    bearing: *const ClrBodyState,
    journal: *const ClrBodyState,
    impact_velocity: f64,
    out: *mut ClrRevoluteForces,
) -> ClrStatus {
    write_out(out, || {
        let joint = borrow("joint", joint)?;
        let a = JointInputs::read(normal, friction, [bearing, journal], BEARING_JOURNAL)?;
        let v0 = finite("impact_velocity (m/s)", impact_velocity)?;
        Ok(revolute_forces(
            &joint.0, a.normal, a.friction, &a.i, &a.j, v0,
        ))
    })
}

/// The revolute joint evaluation shared by the C and Python bindings.
pub fn revolute_forces(
    joint: &RevoluteClearance,
    normal: &NormalLaw,
    friction: Option<&FrictionLaw>,
    bearing: &BodyState,
    journal: &BodyState,
    impact_velocity: f64,
) -> ClrRevoluteForces {
    let c = joint.contact(bearing, journal);
    let forces = if c.in_contact() {
        let f_n = normal.force(c.penetration, c.normal_velocity, impact_velocity);
        let f_t = friction.map_or(0.0, |f| f.force(c.tangential_velocity, f_n));
        c.generalized_forces(f_n, f_t)
    } else {
        JointForces::default()
    };
    ClrRevoluteForces {
        penetration: c.penetration,
        normal_x: c.normal.x,
        normal_y: c.normal.y,
        normal_velocity: c.normal_velocity,
        tangential_velocity: c.tangential_velocity,
        normal_force: forces.normal_force,
        tangential_force: forces.tangential_force,
        bearing: generalized(forces.bearing),
        journal: generalized(forces.journal),
    }
}

/// Free a revolute joint. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `joint` is NULL or a handle from `clr_revolute_joint_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_revolute_joint_free(joint: *mut ClrRevoluteJoint) {
    free_handle(joint)
}

/// Create a LuGre friction model (C. Canudas de Wit, H. Olsson, K.J. Åström, P. Lischinsky, IEEE
/// Trans. Autom. Control 40 (1995) 419–425) in friction-coefficient form:
/// μ = σ₀z + σ₁ż + σ₂v_T, ż = v_T − σ₀|v_T|z/g(v_T), g(v) = μ_c + (μ_s − μ_c)e^{−(v/v_s)²},
/// F_T = −μ F_N. Parameters: bristle stiffness σ₀ (1/m, > 0), bristle damping σ₁ (s/m, ≥ 0),
/// viscous coefficient σ₂ (s/m, ≥ 0), static μ_s (–, > 0) and Coulomb μ_c (–, > 0) coefficients,
/// Stribeck velocity v_s (m/s, > 0). On success `*out` receives a new handle to free with
/// `clr_lugre_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_lugre_new(
    sigma0: f64,
    sigma1: f64,
    sigma2: f64,
    mu_s: f64,
    mu_c: f64,
    v_s: f64,
    out: *mut *mut ClrLuGre,
) -> ClrStatus {
    new_handle(out, || {
        let law = LuGre::new(sigma0, sigma1, sigma2, mu_s, mu_c, v_s)?;
        Ok(ClrLuGre(law))
    })
}

/// Evaluate the LuGre model for the bristle deflection z (m), the slip velocity v_T (m/s) and the
/// normal force F_N (N): the bristle rate ż (m/s) to integrate, the coefficient μ (–) and the
/// friction force F_T = −μ F_N (N, 0 for F_N ≤ 0). The caller keeps z per contact. At constant
/// v_T ≠ 0 the steady state is z = sgn(v_T) g(v_T)/σ₀, where μ = sgn(v_T) g(v_T) + σ₂ v_T.
/// Allocates nothing.
///
/// # Safety
/// `law` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_lugre_evaluate(
    law: *const ClrLuGre,
    z: f64,
    v_t: f64,
    f_n: f64,
    out: *mut ClrLuGreOutput,
) -> ClrStatus {
    write_out(out, || {
        let law = borrow("law", law)?;
        let z = finite("z (m)", z)?;
        let v = finite("v_t (m/s)", v_t)?;
        let f = finite("f_n (N)", f_n)?;
        Ok(lugre_evaluate(&law.0, z, v, f))
    })
}

/// The LuGre evaluation shared by the C and Python bindings.
pub fn lugre_evaluate(law: &LuGre, z: f64, v_t: f64, f_n: f64) -> ClrLuGreOutput {
    let z_dot = law.z_dot(v_t, z);
    ClrLuGreOutput {
        z_dot,
        coefficient: law.coefficient(v_t, z, z_dot),
        friction_force: law.force(v_t, z, z_dot, f_n),
    }
}

/// Free a LuGre model. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `law` is NULL or a handle from `clr_lugre_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_lugre_free(law: *mut ClrLuGre) {
    free_handle(law)
}

/// Create a planar translational clearance joint (P. Flores, J. Ambrósio, J.C.P. Claro, H.M.
/// Lankarani, J. Comput. Nonlinear Dyn. 3 (2008) 011007): a rectangular slider of length L and
/// height h (m, > 0) on body j, centred at (`slider_centre_x`, `slider_centre_y`) (m, local to
/// body j) and rotated by `slider_angle` (rad), moving in a straight guide of inner width W > h
/// (m) on body i whose frame sits at (`guide_origin_x`, `guide_origin_y`) (m, local to body i)
/// rotated by `guide_angle` (rad); the guide surfaces are the lines y = ±W/2 of the guide frame.
/// On success `*out` receives a new handle to free with `clr_translational_joint_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn clr_translational_joint_new(
    guide_width: f64,
    slider_length: f64,
    slider_height: f64,
    guide_origin_x: f64,
    guide_origin_y: f64,
    guide_angle: f64,
    slider_centre_x: f64,
    slider_centre_y: f64,
    slider_angle: f64,
    out: *mut *mut ClrTranslationalJoint,
) -> ClrStatus {
    new_handle(out, || {
        let slider = SliderShape::new(
            slider_length,
            slider_height,
            [slider_centre_x, slider_centre_y].into(),
            slider_angle,
        )?;
        let joint = TranslationalClearance::new(
            slider,
            guide_width,
            [guide_origin_x, guide_origin_y].into(),
            guide_angle,
        )?;
        Ok(ClrTranslationalJoint(joint))
    })
}

/// Generalized forces of the translational clearance joint on both bodies (Flores et al. 2008):
/// every slider corner beyond a guide surface is a point contact with penetration δ, F_N from
/// `normal` with δ̇ = v_N and the impact velocity δ̇⁻ = `impact_velocities[k]` (m/s) of corner k,
/// F_T from `friction` (NULL: frictionless); the force on the slider is −F_N n + F_T t at the
/// corner, the opposite acts on the guide at its contact point, reduced to each body's reference
/// point. `impact_velocities` points to 4 doubles, one per corner (the caller keeps them per
/// contact: the corner's v_N at its first evaluation with δ > 0, until it separates; entries of
/// inactive corners are not read but must be finite). Zero forces in free flight.
///
/// # Safety
/// `joint`, `normal` are NULL or live handles; `friction` is NULL or a live handle; `guide`,
/// `slider` are NULL or point to `ClrBodyState`; `impact_velocities` is NULL or points to 4
/// doubles; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_translational_joint_forces(
    joint: *const ClrTranslationalJoint,
    normal: *const ClrNormalLaw,
    friction: *const ClrFrictionLaw,
    guide: *const ClrBodyState,
    slider: *const ClrBodyState,
    impact_velocities: *const f64,
    out: *mut ClrTranslationalForces,
) -> ClrStatus {
    write_out(out, || {
        let joint = borrow("joint", joint)?;
        let a = JointInputs::read(normal, friction, [guide, slider], GUIDE_SLIDER)?;
        let p = non_null(IMPACT_VELOCITIES, impact_velocities)?;
        const NAMES: [&str; 4] = [
            "impact_velocities[0] (m/s)",
            "impact_velocities[1] (m/s)",
            "impact_velocities[2] (m/s)",
            "impact_velocities[3] (m/s)",
        ];
        let mut v0 = [0.0; 4];
        for (k, v) in v0.iter_mut().enumerate() {
            *v = finite(NAMES[k], p.add(k).read())?;
        }
        Ok(translational_forces(
            &joint.0, a.normal, a.friction, &a.i, &a.j, &v0,
        ))
    })
}

/// The translational joint evaluation shared by the C and Python bindings.
pub fn translational_forces(
    joint: &TranslationalClearance,
    normal: &NormalLaw,
    friction: Option<&FrictionLaw>,
    guide: &BodyState,
    slider: &BodyState,
    impact_velocities: &[f64; 4],
) -> ClrTranslationalForces {
    let c = joint.contact(guide, slider);
    let forces = c.generalized_forces(|cc| {
        let p = &cc.contact;
        let f_n = normal.force(
            p.penetration,
            p.normal_velocity,
            impact_velocities[cc.corner],
        );
        let f_t = friction.map_or(0.0, |f| f.force(p.tangential_velocity, f_n));
        (f_n, f_t)
    });
    let mut corners = [ClrCornerContact::default(); 4];
    for cc in c.active() {
        let p = &cc.contact;
        let (f_n, f_t) = forces.corner_forces[cc.corner];
        corners[cc.corner] = ClrCornerContact {
            active: 1,
            side: match cc.side {
                GuideSide::Upper => 1,
                GuideSide::Lower => -1,
            },
            penetration: p.penetration,
            normal_x: p.normal.x,
            normal_y: p.normal.y,
            normal_velocity: p.normal_velocity,
            tangential_velocity: p.tangential_velocity,
            normal_force: f_n,
            tangential_force: f_t,
        };
    }
    ClrTranslationalForces {
        configuration: match c.configuration {
            Configuration::FreeFlight => CLR_CONFIGURATION_FREE_FLIGHT,
            Configuration::OneCorner => CLR_CONFIGURATION_ONE_CORNER,
            Configuration::TwoCornersOneSurface => CLR_CONFIGURATION_TWO_CORNERS_ONE_SURFACE,
            Configuration::TwoCornersOppositeSurfaces => {
                CLR_CONFIGURATION_TWO_CORNERS_OPPOSITE_SURFACES
            }
            Configuration::MoreCorners => CLR_CONFIGURATION_MORE_CORNERS,
        },
        corners,
        guide: generalized(forces.guide),
        slider: generalized(forces.slider),
    }
}

/// Free a translational joint. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `joint` is NULL or a handle from `clr_translational_joint_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_translational_joint_free(joint: *mut ClrTranslationalJoint) {
    free_handle(joint)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clr_contact::DampingFactor;

    #[test]
    fn constants_match_the_tables() {
        let elastic = [
            CLR_ELASTIC_HERTZ,
            CLR_ELASTIC_POWER,
            CLR_ELASTIC_LINEAR,
            CLR_ELASTIC_HERTZ_SPHERE_SPHERE,
            CLR_ELASTIC_HERTZ_SPHERE_PLANE,
            CLR_ELASTIC_HERTZ_INTERNAL_CYLINDER,
            CLR_ELASTIC_LIU,
            CLR_ELASTIC_BAI_ZHAO,
            CLR_ELASTIC_PEREIRA_INTERNAL,
            CLR_ELASTIC_PEREIRA_EXTERNAL,
            CLR_ELASTIC_JOHNSON,
        ];
        for (&k, code) in ElasticKind::ALL.iter().zip(elastic) {
            assert_eq!(ElasticKind::from_code(code).unwrap(), k);
        }
        let damping = [
            (CLR_DAMPING_NONE, DampingFactor::None),
            (CLR_DAMPING_HUNT_CROSSLEY, DampingFactor::HuntCrossley),
            (
                CLR_DAMPING_LANKARANI_NIKRAVESH,
                DampingFactor::LankaraniNikravesh,
            ),
            (CLR_DAMPING_FLORES, DampingFactor::Flores),
            (CLR_DAMPING_GONTHIER, DampingFactor::Gonthier),
            (CLR_DAMPING_ZHIYING_QISHAO, DampingFactor::ZhiyingQishao),
            (CLR_DAMPING_HU_GUO, DampingFactor::HuGuo),
            (CLR_DAMPING_GHARIB_HURMUZLU, DampingFactor::GharibHurmuzlu),
            (
                CLR_DAMPING_HERBERT_MCWHANNELL,
                DampingFactor::HerbertMcWhannell,
            ),
            (CLR_DAMPING_LEE_WANG, DampingFactor::LeeWang),
            (CLR_DAMPING_EXACT, DampingFactor::Exact),
        ];
        assert_eq!(damping.len(), DampingFactor::ALL.len());
        for (code, d) in damping {
            assert_eq!(damping_from_code(code).unwrap(), d);
        }
        let friction = [
            (CLR_FRICTION_COULOMB, FrictionKind::Coulomb),
            (CLR_FRICTION_AMBROSIO, FrictionKind::Ambrosio),
            (CLR_FRICTION_THRELFALL, FrictionKind::Threlfall),
            (CLR_FRICTION_STRIBECK, FrictionKind::Stribeck),
        ];
        for (code, k) in friction {
            assert_eq!(FrictionKind::from_code(code).unwrap(), k);
        }
    }

    #[test]
    fn lugre_matches_the_rust_model_bit_for_bit() {
        let (s0, s1, s2, mu_s, mu_c, v_s) = (1e5, 316.0, 0.4, 0.3, 0.2, 0.01);
        let rust = LuGre::new(s0, s1, s2, mu_s, mu_c, v_s).unwrap();
        let mut h: *mut ClrLuGre = std::ptr::null_mut();
        let s = unsafe { clr_lugre_new(s0, s1, s2, mu_s, mu_c, v_s, &mut h) };
        assert_eq!(s, ClrStatus::Ok);
        for (z, v, f_n) in [
            (0.0, 0.0, 100.0),
            (1e-6, 0.005, 1000.0),
            (-2e-6, -0.02, 250.0),
            (3e-6, 0.1, -5.0),
            (2.9e-6, 1e-4, 0.0),
        ] {
            let mut out = ClrLuGreOutput::default();
            let s = unsafe { clr_lugre_evaluate(h, z, v, f_n, &mut out) };
            assert_eq!(s, ClrStatus::Ok);
            let z_dot = rust.z_dot(v, z);
            assert_eq!(out.z_dot.to_bits(), z_dot.to_bits());
            assert_eq!(
                out.coefficient.to_bits(),
                rust.coefficient(v, z, z_dot).to_bits()
            );
            assert_eq!(
                out.friction_force.to_bits(),
                rust.force(v, z, z_dot, f_n).to_bits()
            );
        }
        let mut out = ClrLuGreOutput {
            z_dot: 7.0,
            ..Default::default()
        };
        let s = unsafe { clr_lugre_evaluate(h, f64::NAN, 0.1, 1.0, &mut out) };
        assert_eq!(s, ClrStatus::NonFinite);
        assert_eq!(out.z_dot, 7.0);
        unsafe { clr_lugre_free(h) };
        let mut bad: *mut ClrLuGre = std::ptr::null_mut();
        let s = unsafe { clr_lugre_new(0.0, s1, s2, mu_s, mu_c, v_s, &mut bad) };
        assert_eq!(s, ClrStatus::InvalidParameter);
        assert!(bad.is_null());
        assert_eq!(
            unsafe { clr_lugre_evaluate(std::ptr::null(), 0.0, 0.0, 0.0, &mut out) },
            ClrStatus::NullPointer
        );
    }

    #[test]
    fn translational_forces_match_the_rust_api_bit_for_bit() {
        // Slider 40 mm x 20 mm in a 20.2 mm guide, tilted by 2 mrad and pushed 50 um below the
        // lower face, moving down-right and spinning: corners 0 and 3 touch the faces.
        let (w, l, h) = (0.0202, 0.04, 0.02);
        let shape = SliderShape::new(l, h, [0.001, 0.0].into(), 0.0).unwrap();
        let rust = TranslationalClearance::new(shape, w, [0.0, 0.002].into(), 0.01).unwrap();
        let mut joint: *mut ClrTranslationalJoint = std::ptr::null_mut();
        let s = unsafe {
            clr_translational_joint_new(w, l, h, 0.0, 0.002, 0.01, 0.001, 0.0, 0.0, &mut joint)
        };
        assert_eq!(s, ClrStatus::Ok);
        let jb = JournalBearing::flap_paper_test();
        let normal = NormalLaw::preset("LN", &jb, 0.5).unwrap();
        let friction = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap();
        let (cn, cf) = (ClrNormalLaw(normal), ClrFrictionLaw(friction));
        let guide = ClrBodyState {
            x: 0.01,
            y: -0.002,
            theta: -0.01,
            vx: 0.1,
            vy: 0.0,
            omega: 0.5,
        };
        let slider = ClrBodyState {
            x: 0.3,
            y: -0.00015,
            theta: 0.002,
            vx: 0.5,
            vy: -0.2,
            omega: 3.0,
        };
        let v0 = [0.2, 0.3, 0.4, 0.5];
        let mut out = ClrTranslationalForces::default();
        let s = unsafe {
            clr_translational_joint_forces(joint, &cn, &cf, &guide, &slider, v0.as_ptr(), &mut out)
        };
        assert_eq!(s, ClrStatus::Ok);
        let bi = body_state("g", &guide).unwrap();
        let bj = body_state("s", &slider).unwrap();
        let c = rust.contact(&bi, &bj);
        assert_ne!(c.configuration, Configuration::FreeFlight);
        let f = c.generalized_forces(|cc| {
            let p = &cc.contact;
            let f_n = normal.force(p.penetration, p.normal_velocity, v0[cc.corner]);
            (f_n, friction.force(p.tangential_velocity, f_n))
        });
        let bits = |g: &ClrGeneralizedForce| [g.fx.to_bits(), g.fy.to_bits(), g.moment.to_bits()];
        assert_eq!(bits(&out.guide), bits(&generalized(f.guide)));
        assert_eq!(bits(&out.slider), bits(&generalized(f.slider)));
        let mut active = 0;
        for k in 0..4 {
            let o = &out.corners[k];
            match &c.corners[k] {
                Some(cc) => {
                    active += 1;
                    assert_eq!(o.active, 1);
                    assert!(o.normal_force > 0.0);
                    assert_eq!(o.normal_force.to_bits(), f.corner_forces[k].0.to_bits());
                    assert_eq!(o.tangential_force.to_bits(), f.corner_forces[k].1.to_bits());
                    assert_eq!(o.penetration.to_bits(), cc.contact.penetration.to_bits());
                    assert_eq!(o.normal_y.to_bits(), cc.contact.normal.y.to_bits());
                    assert_eq!(
                        o.tangential_velocity.to_bits(),
                        cc.contact.tangential_velocity.to_bits()
                    );
                }
                None => assert_eq!(*o, ClrCornerContact::default()),
            }
        }
        assert!(active >= 1);

        // Errors: NULL impact velocities, NaN state, W <= h.
        let s = unsafe {
            clr_translational_joint_forces(
                joint,
                &cn,
                &cf,
                &guide,
                &slider,
                std::ptr::null(),
                &mut out,
            )
        };
        assert_eq!(s, ClrStatus::NullPointer);
        let nan = ClrBodyState {
            omega: f64::NAN,
            ..slider
        };
        let s = unsafe {
            clr_translational_joint_forces(
                joint,
                &cn,
                std::ptr::null(),
                &guide,
                &nan,
                v0.as_ptr(),
                &mut out,
            )
        };
        assert_eq!(s, ClrStatus::NonFinite);
        unsafe { clr_translational_joint_free(joint) };
        let mut bad: *mut ClrTranslationalJoint = std::ptr::null_mut();
        let s =
            unsafe { clr_translational_joint_new(h, l, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, &mut bad) };
        assert_eq!(s, ClrStatus::InvalidParameter);
        assert!(bad.is_null());
    }
}
