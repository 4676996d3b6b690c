//! The problem definition: `M(t, y) y' = f(t, y)` with optional Jacobian, mass matrix and events.

/// Crossing direction that triggers an event function g(t, y).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Direction {
    /// g goes from negative to zero or positive.
    Rising,
    /// g goes from positive to zero or negative.
    Falling,
    /// Either crossing.
    #[default]
    Both,
}

impl Direction {
    /// True when the change of g from `g_old` to `g_new` over one step is a crossing in this
    /// direction. A step that starts exactly on g = 0 never triggers (the crossing belongs to
    /// the previous step, or to the restart point).
    pub fn triggered(self, g_old: f64, g_new: f64) -> bool {
        let rising = g_old < 0.0 && g_new >= 0.0;
        let falling = g_old > 0.0 && g_new <= 0.0;
        match self {
            Direction::Rising => rising,
            Direction::Falling => falling,
            Direction::Both => rising || falling,
        }
    }
}

/// What kind of mass matrix M multiplies y' on the left.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MassKind {
    /// M = I: an explicit ODE y' = f(t, y).
    #[default]
    Identity,
    /// M constant, evaluated once per run (it may be singular: index-1 DAE).
    Constant,
    /// M(t, y), evaluated at the predicted state of every step attempt. The Newton matrix
    /// M − hγJ omits the derivative of M with respect to y (as ode15s does), which costs
    /// Newton iterations only when M varies strongly over one step.
    StateDependent,
}

/// A problem `M(t, y) y' = f(t, y)` with event functions g(t, y).
///
/// Dense matrices (Jacobian, mass) are column-major n × n slices: entry (i, j) is at
/// `m[i + j * n]`. They are zeroed before each call, so only non-zeros need to be written.
/// Units are those of the model; t is usually seconds.
pub trait OdeSystem {
    /// Number of state components n (≥ 1).
    fn dim(&self) -> usize;

    /// The right-hand side f(t, y), written into `dydt` (length n).
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]);

    /// True when [`OdeSystem::jacobian`] is implemented; otherwise the NDF solver uses
    /// forward finite differences with scaled increments.
    fn has_jacobian(&self) -> bool {
        false
    }

    /// The Jacobian ∂f/∂y (column-major, zeroed before the call).
    fn jacobian(&mut self, _t: f64, _y: &[f64], _jac: &mut [f64]) {}

    /// True when the system solves the Newton systems of implicit methods itself
    /// ([`OdeSystem::newton_jacobian`], [`OdeSystem::newton_factor`],
    /// [`OdeSystem::newton_solve`]) instead of handing a dense Jacobian to the solver: for
    /// problems whose structure (sparsity, a second-order form, constraint multipliers) makes a
    /// smaller or sparse factorization possible, in the manner of the linear-solver interface of
    /// SUNDIALS (`lsetup`/`lsolve`; Hindmarsh et al., ACM TOMS 31 (2005) 363–396, §5).
    /// [`OdeSystem::jacobian`] and [`OdeSystem::has_jacobian`] are then not used by NDF.
    fn has_newton_solver(&self) -> bool {
        false
    }

    /// Evaluate and keep the Jacobian ∂f/∂y at (t, y) for the following
    /// [`OdeSystem::newton_factor`] calls (the solver reuses it over several steps and step
    /// sizes, as it does a dense Jacobian). Returns false when it is not finite.
    fn newton_jacobian(&mut self, _t: f64, _y: &[f64]) -> bool {
        false
    }

    /// Form and factor M − c·J with the kept Jacobian J and the mass matrix M (c > 0, units of
    /// t). Returns false when the matrix is singular.
    fn newton_factor(&mut self, _c: f64) -> bool {
        false
    }

    /// Solve (M − c·J) x = b in place with the last successful factorization (`b` becomes x).
    /// An approximate solve is allowed (simplified Newton converges with an approximate J; a
    /// poor one costs iterations and Jacobian evaluations, which the statistics show).
    fn newton_solve(&mut self, _b: &mut [f64]) {}

    /// The kind of mass matrix (identity by default).
    fn mass_kind(&self) -> MassKind {
        MassKind::Identity
    }

    /// The mass matrix M(t, y) (column-major, zeroed before the call). Called only when
    /// [`OdeSystem::mass_kind`] is not `Identity`. A singular M makes the problem an index-1
    /// DAE; its initial state must then be consistent (the algebraic equations satisfied).
    fn mass(&mut self, _t: f64, _y: &[f64], _m: &mut [f64]) {}

    /// Number of event functions.
    fn n_events(&self) -> usize {
        0
    }

    /// The event functions g(t, y), written into `g` (length [`OdeSystem::n_events`]).
    fn events(&mut self, _t: f64, _y: &[f64], _g: &mut [f64]) {}

    /// Crossing direction of event `i` (both by default).
    fn event_direction(&self, _i: usize) -> Direction {
        Direction::Both
    }

    /// Whether event `i` stops the run (false by default: the event is only recorded).
    fn event_terminal(&self, _i: usize) -> bool {
        false
    }

    /// An upper bound on the next step from the state at its start, s (default: none). The
    /// solvers take min(h, `h_max`, this) for every step, so a model can keep fast bodies from
    /// passing through each other within one step, where an event function sampled at step
    /// ends would miss the contact.
    fn max_step(&mut self, _t: f64, _y: &[f64]) -> f64 {
        f64::INFINITY
    }

    /// Checks the problem's own data before a run (for example a mass matrix of the wrong
    /// size); an `Err(message)` becomes [`crate::OdeError::InvalidInput`].
    fn validate(&self) -> Result<(), String> {
        Ok(())
    }
}

/// Forward every method of [`OdeSystem`] through a pointer type.
macro_rules! forward_ode_system {
    ($ptr:ty) => {
        impl<S: OdeSystem + ?Sized> OdeSystem for $ptr {
            fn dim(&self) -> usize {
                (**self).dim()
            }
            fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
                (**self).rhs(t, y, dydt)
            }
            fn has_jacobian(&self) -> bool {
                (**self).has_jacobian()
            }
            fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut [f64]) {
                (**self).jacobian(t, y, jac)
            }
            fn has_newton_solver(&self) -> bool {
                (**self).has_newton_solver()
            }
            fn newton_jacobian(&mut self, t: f64, y: &[f64]) -> bool {
                (**self).newton_jacobian(t, y)
            }
            fn newton_factor(&mut self, c: f64) -> bool {
                (**self).newton_factor(c)
            }
            fn newton_solve(&mut self, b: &mut [f64]) {
                (**self).newton_solve(b)
            }
            fn mass_kind(&self) -> MassKind {
                (**self).mass_kind()
            }
            fn mass(&mut self, t: f64, y: &[f64], m: &mut [f64]) {
                (**self).mass(t, y, m)
            }
            fn n_events(&self) -> usize {
                (**self).n_events()
            }
            fn events(&mut self, t: f64, y: &[f64], g: &mut [f64]) {
                (**self).events(t, y, g)
            }
            fn event_direction(&self, i: usize) -> Direction {
                (**self).event_direction(i)
            }
            fn event_terminal(&self, i: usize) -> bool {
                (**self).event_terminal(i)
            }
            fn max_step(&mut self, t: f64, y: &[f64]) -> f64 {
                (**self).max_step(t, y)
            }
            fn validate(&self) -> Result<(), String> {
                (**self).validate()
            }
        }
    };
}

forward_ode_system!(&mut S);
forward_ode_system!(Box<S>);

/// Signature of a Jacobian closure: `(t, y, jac)` with `jac` column-major n × n.
pub type JacFn = fn(f64, &[f64], &mut [f64]);

type BoxedMatFn = Box<dyn FnMut(f64, &[f64], &mut [f64])>;
type BoxedEventFn = Box<dyn FnMut(f64, &[f64]) -> f64>;

enum FnMass {
    Identity,
    Constant(Vec<f64>),
    State(BoxedMatFn),
}

struct FnEvent {
    direction: Direction,
    terminal: bool,
    g: BoxedEventFn,
}

/// A problem built from closures.
///
/// ```
/// use clr_ode::{Direction, OdeFn, OdeSystem};
/// // y' = -y with an analytic Jacobian and a terminal event at y = 0.5
/// let mut sys = OdeFn::new(1, |_t, y: &[f64], dy: &mut [f64]| dy[0] = -y[0])
///     .jacobian(|_t, _y: &[f64], j: &mut [f64]| j[0] = -1.0)
///     .event(Direction::Falling, true, |_t, y: &[f64]| y[0] - 0.5);
/// assert_eq!(sys.dim(), 1);
/// assert_eq!(sys.n_events(), 1);
/// ```
pub struct OdeFn<F, J = JacFn> {
    dim: usize,
    f: F,
    jac: Option<J>,
    mass: FnMass,
    events: Vec<FnEvent>,
}

impl<F: FnMut(f64, &[f64], &mut [f64])> OdeFn<F, JacFn> {
    /// A system of dimension `dim` with right-hand side `f(t, y, dydt)`.
    pub fn new(dim: usize, f: F) -> Self {
        OdeFn {
            dim,
            f,
            jac: None,
            mass: FnMass::Identity,
            events: Vec::new(),
        }
    }
}

impl<F: FnMut(f64, &[f64], &mut [f64]), J: FnMut(f64, &[f64], &mut [f64])> OdeFn<F, J> {
    /// Attach an analytic Jacobian `jac(t, y, J)` (J column-major n × n, zeroed before the call).
    pub fn jacobian<J2: FnMut(f64, &[f64], &mut [f64])>(self, jac: J2) -> OdeFn<F, J2> {
        OdeFn {
            dim: self.dim,
            f: self.f,
            jac: Some(jac),
            mass: self.mass,
            events: self.events,
        }
    }

    /// Attach a constant mass matrix (column-major n × n; may be singular for an index-1 DAE).
    /// A matrix of the wrong length is reported as invalid input when a solver starts.
    pub fn mass(mut self, m: Vec<f64>) -> Self {
        self.mass = FnMass::Constant(m);
        self
    }

    /// Attach a state-dependent mass matrix `m(t, y, M)` (column-major, zeroed before the call).
    pub fn mass_fn(mut self, m: impl FnMut(f64, &[f64], &mut [f64]) + 'static) -> Self {
        self.mass = FnMass::State(Box::new(m));
        self
    }

    /// Add an event function g(t, y) with its crossing direction and terminal flag.
    pub fn event(
        mut self,
        direction: Direction,
        terminal: bool,
        g: impl FnMut(f64, &[f64]) -> f64 + 'static,
    ) -> Self {
        self.events.push(FnEvent {
            direction,
            terminal,
            g: Box::new(g),
        });
        self
    }
}

impl<F: FnMut(f64, &[f64], &mut [f64]), J: FnMut(f64, &[f64], &mut [f64])> OdeSystem
    for OdeFn<F, J>
{
    fn dim(&self) -> usize {
        self.dim
    }
    #[inline]
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        (self.f)(t, y, dydt)
    }
    fn has_jacobian(&self) -> bool {
        self.jac.is_some()
    }
    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut [f64]) {
        if let Some(j) = self.jac.as_mut() {
            j(t, y, jac)
        }
    }
    fn mass_kind(&self) -> MassKind {
        match self.mass {
            FnMass::Identity => MassKind::Identity,
            FnMass::Constant(_) => MassKind::Constant,
            FnMass::State(_) => MassKind::StateDependent,
        }
    }
    fn mass(&mut self, t: f64, y: &[f64], m: &mut [f64]) {
        match &mut self.mass {
            FnMass::Identity => {
                for i in 0..self.dim {
                    m[i + i * self.dim] = 1.0;
                }
            }
            FnMass::Constant(c) => {
                let k = c.len().min(m.len());
                m[..k].copy_from_slice(&c[..k]);
            }
            FnMass::State(f) => f(t, y, m),
        }
    }
    fn n_events(&self) -> usize {
        self.events.len()
    }
    fn events(&mut self, t: f64, y: &[f64], g: &mut [f64]) {
        for (e, gi) in self.events.iter_mut().zip(g.iter_mut()) {
            *gi = (e.g)(t, y);
        }
    }
    fn event_direction(&self, i: usize) -> Direction {
        self.events.get(i).map_or(Direction::Both, |e| e.direction)
    }
    fn event_terminal(&self, i: usize) -> bool {
        self.events.get(i).is_some_and(|e| e.terminal)
    }
    fn validate(&self) -> Result<(), String> {
        match &self.mass {
            FnMass::Constant(m) if m.len() != self.dim * self.dim => Err(format!(
                "the constant mass matrix has {} entries; a {n} x {n} column-major matrix needs {}",
                m.len(),
                self.dim * self.dim,
                n = self.dim
            )),
            _ => Ok(()),
        }
    }
}
