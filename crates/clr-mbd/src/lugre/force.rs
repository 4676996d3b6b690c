//! The forces of a LuGre clearance joint and its bristle rates (module docs of
//! [`crate::lugre`]), evaluated by the assembly like the stateless clearance joints.

use clr_contact::{BodyState, ContactMemory, LuGre};

use super::state::{Bristles, LuGreContact};
use crate::clearance::{Clearance, ClearanceKind};
use crate::contact_report::ContactReport;

/// ż and F_T of one contact point.
#[inline]
fn bristle(law: &LuGre, v: f64, z: f64, f_n: f64) -> (f64, f64) {
    let z_dot = law.z_dot(v, z);
    (law.force(v, z, z_dot, f_n), z_dot)
}

/// The forces of a LuGre clearance joint (element `k` of the model), added through
/// `add(body, [f_x, f_y, m])`; its bristle rates written to `states`. The geometry, normal law,
/// contact memory and report are those of [`Clearance::apply`], with the LuGre force as the
/// tangential force of each active point.
#[allow(clippy::too_many_arguments)]
pub(crate) fn apply(
    cl: &Clearance,
    lugre: &LuGreContact,
    k: usize,
    bi: &BodyState,
    bj: &BodyState,
    memory: &mut ContactMemory,
    states: &mut Bristles,
    mut add: impl FnMut(usize, [f64; 3]),
) -> ContactReport {
    let mut rep = ContactReport::default();
    let law = &lugre.law;
    let first = lugre.first;
    let Bristles { z, z_dot, mean } = states;
    match &cl.kind {
        ClearanceKind::Revolute(g, application) => {
            let ct = g.contact(bi, bj);
            let local = bi.to_local(bi.position + ct.eccentricity_vector);
            rep.penetration = ct.penetration;
            rep.penetration_rate = ct.normal_velocity;
            rep.eccentricity = [local.x, local.y];
            z_dot[first] = 0.0;
            mean[k] = z[first];
            if ct.in_contact() {
                let vm = memory.impact_velocity(cl.mem, ct.penetration, ct.normal_velocity);
                let f_n = cl.normal.force(ct.penetration, ct.normal_velocity, vm);
                let v = ct.tangential_velocity;
                let (f_t, rate) = bristle(law, v, z[first], f_n);
                z_dot[first] = rate;
                let jf = ct.generalized_forces_with(f_n, f_t, *application);
                add(cl.i, jf.bearing.as_array());
                add(cl.j, jf.journal.as_array());
                rep.active_points = 1;
                rep.normal_force = jf.normal_force;
                rep.friction_force = jf.tangential_force;
                rep.dissipated_power = crate::clearance::revolute_dissipated_power(
                    &jf,
                    bi,
                    bj,
                    cl.normal.elastic_force(ct.penetration) * ct.normal_velocity,
                );
            }
        }
        ClearanceKind::Translational {
            geometry,
            origin,
            angle,
            ..
        } => {
            let ct = geometry.contact(bi, bj);
            let local = bi.to_local(bj.position);
            let rel = local - *origin;
            let (s, c) = angle.sin_cos();
            rep.eccentricity = [c * rel.x + s * rel.y, -s * rel.x + c * rel.y];
            let zs = &z[first..first + 4];
            let rates = &mut z_dot[first..first + 4];
            rates.fill(0.0);
            let normal = &cl.normal;
            let (mut n_active, mut power, mut zf, mut f_sum) = (0, 0.0, 0.0, 0.0);
            let f = ct.generalized_forces(|corner| {
                let pc = &corner.contact;
                let p = corner.corner;
                let vm = memory.impact_velocity(cl.mem + p, pc.penetration, pc.normal_velocity);
                let f_n = normal.force(pc.penetration, pc.normal_velocity, vm);
                let (f_t, rate) = bristle(law, pc.tangential_velocity, zs[p], f_n);
                rates[p] = rate;
                n_active += 1;
                power += (f_n - normal.elastic_force(pc.penetration)) * pc.normal_velocity
                    - f_t * pc.tangential_velocity;
                if f_n > 0.0 {
                    zf += f_n * zs[p];
                    f_sum += f_n;
                }
                (f_n, f_t)
            });
            mean[k] = if f_sum > 0.0 {
                zf / f_sum
            } else {
                zs.iter().sum::<f64>() / 4.0
            };
            cl.report_corners(bi, bj, &f, (n_active, power), &mut rep, &mut add);
        }
        // refused when the element is compiled (`FrictionSpec::build`): a slider on a flexible
        // guide takes stateless laws only
        // LuGre is refused for these at compile time
        ClearanceKind::FlexGuide(_) | ClearanceKind::Shapes(_) | ClearanceKind::FacePair(_) => {}
    }
    rep
}
