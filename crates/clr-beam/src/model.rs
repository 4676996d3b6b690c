//! Meshes of straight beams and planar frames, boundary conditions, assembly and statics.
//!
//! Global DOF numbering: node i owns DOF 3i (u, along global x), 3i + 1 (v, along global y) and
//! 3i + 2 (θ, counter-clockwise rotation). Forces and moments follow the same signs.

use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, MatRef, Side};

use crate::element::{FrameElement, MassKind, Mat6, Vec6};
use crate::error::BeamError;
use crate::section::{Material, Section};

/// Sparse (CSC) matrix type of the assembly.
pub type SparseMatrix = SparseColMat<usize, f64>;

/// Planar frame model: nodes, elements, supports, mass kind and Rayleigh damping.
#[derive(Debug, Clone, Default)]
pub struct BeamModel {
    nodes: Vec<[f64; 2]>,
    elements: Vec<FrameElement>,
    /// Prescribed value per DOF (`None` = free).
    prescribed: Vec<Option<f64>>,
    mass_kind: MassKind,
    rayleigh: (f64, f64),
}

/// Support of a node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Support {
    /// u = v = θ = 0.
    Clamped,
    /// u = v = 0, θ free.
    Pinned,
    /// Rolls along global x: v = 0, u and θ free.
    RollerX,
    /// Rolls along global y: u = 0, v and θ free.
    RollerY,
    /// No constraint (removes earlier constraints of the node).
    Free,
}

/// Loads: nodal forces/moments and uniform distributed loads on elements.
#[derive(Debug, Clone, Default)]
pub struct Loads {
    nodal: Vec<(usize, [f64; 3])>,
    uniform_local: Vec<(usize, f64, f64)>,
    uniform_global: Vec<(usize, [f64; 2])>,
}

impl Loads {
    /// No load.
    pub fn new() -> Self {
        Self::default()
    }

    /// Force (F_x, F_y) in N and moment M in N·m (counter-clockwise) at a node.
    pub fn nodal(mut self, node: usize, force: [f64; 3]) -> Self {
        self.nodal.push((node, force));
        self
    }

    /// Uniform load on an element in its local axes: axial p and transverse q in N/m (q along
    /// the element normal, i.e. the axis rotated by +90°).
    pub fn uniform_local(mut self, element: usize, axial: f64, transverse: f64) -> Self {
        self.uniform_local.push((element, axial, transverse));
        self
    }

    /// Uniform load on an element with global components (w_x, w_y) in N per metre of element
    /// length (e.g. self weight: (0, −ρ A g)).
    pub fn uniform_global(mut self, element: usize, w: [f64; 2]) -> Self {
        self.uniform_global.push((element, w));
        self
    }

    /// Uniform global load on every element of a model.
    pub fn uniform_global_all(mut self, model: &BeamModel, w: [f64; 2]) -> Self {
        for e in 0..model.elements.len() {
            self.uniform_global.push((e, w));
        }
        self
    }

    /// The self weight of every element of `model` under the gravitational acceleration
    /// `g` = (g_x, g_y) in m/s²: a uniform global load ρA·g (N/m) on each element, whose
    /// consistent (work-equivalent) nodal loads f = ∫Nᵀ ρA g dx ([`FrameElement::uniform_load`];
    /// Przemieniecki 1968 ch. 5, Cook et al. 2002 ch. 2) are the exact gradient of the potential
    /// −g·∫ρA (r + u) dx of the interpolated displacement field.
    pub fn self_weight(mut self, model: &BeamModel, g: [f64; 2]) -> Self {
        for (e, el) in model.elements.iter().enumerate() {
            self.uniform_global
                .push((e, [el.rho_a * g[0], el.rho_a * g[1]]));
        }
        self
    }

    /// Assemble the global load vector (length 3 × nodes) of `model`.
    pub fn vector(&self, model: &BeamModel) -> Result<Vec<f64>, BeamError> {
        let mut f = vec![0.0; model.n_dof()];
        for &(n, v) in &self.nodal {
            model.check_node(n)?;
            for c in 0..3 {
                f[3 * n + c] += v[c];
            }
        }
        let mut add = |e: usize, fe: Vec6| -> Result<(), BeamError> {
            let el = model.element(e)?;
            for (i, d) in el.dofs().into_iter().enumerate() {
                f[d] += fe[i];
            }
            Ok(())
        };
        for &(e, p, q) in &self.uniform_local {
            let el = *model.element(e)?;
            add(e, el.uniform_load(p, q))?;
        }
        for &(e, w) in &self.uniform_global {
            let el = *model.element(e)?;
            let p = w[0] * el.cos + w[1] * el.sin;
            let q = -w[0] * el.sin + w[1] * el.cos;
            add(e, el.uniform_load(p, q))?;
        }
        Ok(f)
    }
}

/// Which DOF are free and where they sit in the reduced (free) ordering.
#[derive(Debug, Clone, PartialEq)]
pub struct DofMap {
    /// Full DOF indices of the free DOF, ascending.
    pub free: Vec<usize>,
    /// Full DOF indices of the constrained DOF, ascending.
    pub constrained: Vec<usize>,
    /// For each full DOF, its index among the free DOF.
    pub free_index: Vec<Option<usize>>,
}

/// Result of a static analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticSolution {
    /// Nodal displacements (m, rad), full ordering (3 per node).
    pub displacements: Vec<f64>,
    /// Support reactions (N, N·m), full ordering; zero at free DOF.
    pub reactions: Vec<f64>,
}

impl BeamModel {
    /// An empty model.
    pub fn new() -> Self {
        Self::default()
    }

    /// A straight beam from `start` to `end` (m) divided into `n_elements` equal elements of
    /// one material and section; nodes 0..=n are numbered from `start` to `end`, elements 0..n
    /// in the same order (element i joins nodes i and i + 1).
    pub fn straight(
        start: [f64; 2],
        end: [f64; 2],
        n_elements: usize,
        material: Material,
        section: Section,
    ) -> Result<Self, BeamError> {
        let mut m = Self::new();
        if n_elements == 0 {
            return Err(BeamError::NoElements);
        }
        for i in 0..=n_elements {
            let t = i as f64 / n_elements as f64;
            m.add_node([
                start[0] + t * (end[0] - start[0]),
                start[1] + t * (end[1] - start[1]),
            ]);
        }
        m.add_elements(0, &(1..=n_elements).collect::<Vec<_>>(), material, section)?;
        Ok(m)
    }

    /// Add a node at (x, y) m; returns its index.
    pub fn add_node(&mut self, position: [f64; 2]) -> usize {
        self.nodes.push(position);
        self.prescribed.extend([None, None, None]);
        self.nodes.len() - 1
    }

    /// Add a straight member from node `a` to node `b`, divided into `n_elements` equal
    /// elements (intermediate nodes are created). Returns the element indices, in order from
    /// `a` to `b`. The members of a frame are rigidly connected at shared nodes.
    pub fn add_member(
        &mut self,
        a: usize,
        b: usize,
        n_elements: usize,
        material: Material,
        section: Section,
    ) -> Result<Vec<usize>, BeamError> {
        self.check_node(a)?;
        self.check_node(b)?;
        if n_elements == 0 {
            return Err(BeamError::NoElements);
        }
        // Validate everything before creating the intermediate nodes.
        let (material, section) = validated(material, section)?;
        let [pa, _] = self.member_axis(a, b)?;
        let d = [self.nodes[b][0] - pa[0], self.nodes[b][1] - pa[1]];
        let mut chain = Vec::with_capacity(n_elements);
        for i in 1..n_elements {
            let t = i as f64 / n_elements as f64;
            chain.push(self.add_node([pa[0] + t * d[0], pa[1] + t * d[1]]));
        }
        chain.push(b);
        self.add_elements(a, &chain, material, section)
    }

    /// Start position and unit axis of the member a → b; errors on zero length.
    fn member_axis(&self, a: usize, b: usize) -> Result<[[f64; 2]; 2], BeamError> {
        let (pa, pb) = (self.nodes[a], self.nodes[b]);
        let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
        let len = dx.hypot(dy);
        if !(len.is_finite() && len > 0.0) {
            return Err(BeamError::ZeroLength(a, b));
        }
        Ok([pa, [dx / len, dy / len]])
    }

    /// Equal elements from node `a` through the nodes of `chain` (collinear and equally
    /// spaced, the last one being the member's end).
    fn add_elements(
        &mut self,
        a: usize,
        chain: &[usize],
        material: Material,
        section: Section,
    ) -> Result<Vec<usize>, BeamError> {
        let (material, section) = validated(material, section)?;
        let b = chain[chain.len() - 1];
        let [_, axis] = self.member_axis(a, b)?;
        let len = (self.nodes[b][0] - self.nodes[a][0]).hypot(self.nodes[b][1] - self.nodes[a][1]);
        let mut ids = Vec::with_capacity(chain.len());
        let mut prev = a;
        for &next in chain {
            self.elements.push(FrameElement {
                nodes: [prev, next],
                length: len / chain.len() as f64,
                cos: axis[0],
                sin: axis[1],
                ea: material.youngs_modulus * section.area,
                ei: material.youngs_modulus * section.second_moment,
                rho_a: material.density * section.area,
                depth: section.depth,
                axial_force: 0.0,
            });
            ids.push(self.elements.len() - 1);
            prev = next;
        }
        Ok(ids)
    }

    /// Apply a support to a node (replaces the node's earlier constraints).
    pub fn support(&mut self, node: usize, support: Support) -> Result<&mut Self, BeamError> {
        self.check_node(node)?;
        let fixed = match support {
            Support::Clamped => [true, true, true],
            Support::Pinned => [true, true, false],
            Support::RollerX => [false, true, false],
            Support::RollerY => [true, false, false],
            Support::Free => [false, false, false],
        };
        for (c, f) in fixed.into_iter().enumerate() {
            self.prescribed[3 * node + c] = f.then_some(0.0);
        }
        Ok(self)
    }

    /// Prescribe DOF component `component` (0 = u, 1 = v, 2 = θ) of `node` to `value` (m or rad).
    pub fn prescribe(
        &mut self,
        node: usize,
        component: usize,
        value: f64,
    ) -> Result<&mut Self, BeamError> {
        self.check_node(node)?;
        if component > 2 {
            return Err(BeamError::NoSuchComponent(component));
        }
        self.prescribed[3 * node + component] = Some(value);
        Ok(self)
    }

    /// Set the axial force P (N, tension positive) of an element for the geometric stiffness.
    pub fn set_axial_force(&mut self, element: usize, force: f64) -> Result<&mut Self, BeamError> {
        self.check_element(element)?;
        self.elements[element].axial_force = force;
        Ok(self)
    }

    /// Choose consistent (default) or lumped mass.
    pub fn set_mass_kind(&mut self, kind: MassKind) -> &mut Self {
        self.mass_kind = kind;
        self
    }

    /// Rayleigh damping C = α M + β K (α in 1/s, β in s); default (0, 0).
    pub fn set_rayleigh(&mut self, alpha: f64, beta: f64) -> &mut Self {
        self.rayleigh = (alpha, beta);
        self
    }

    /// Rayleigh coefficients (α, β).
    pub fn rayleigh(&self) -> (f64, f64) {
        self.rayleigh
    }

    /// Mass kind in use.
    pub fn mass_kind(&self) -> MassKind {
        self.mass_kind
    }

    /// Node positions (m).
    pub fn nodes(&self) -> &[[f64; 2]] {
        &self.nodes
    }

    /// Elements.
    pub fn elements(&self) -> &[FrameElement] {
        &self.elements
    }

    /// One element.
    pub fn element(&self, e: usize) -> Result<&FrameElement, BeamError> {
        self.check_element(e)?;
        Ok(&self.elements[e])
    }

    /// Number of DOF (3 per node).
    pub fn n_dof(&self) -> usize {
        3 * self.nodes.len()
    }

    /// Prescribed values per full DOF (`None` = free).
    pub fn prescribed(&self) -> &[Option<f64>] {
        &self.prescribed
    }

    /// Total mass Σ ρ A L (kg).
    pub fn total_mass(&self) -> f64 {
        self.elements.iter().map(|e| e.rho_a * e.length).sum()
    }

    pub(crate) fn check_node(&self, n: usize) -> Result<(), BeamError> {
        if n < self.nodes.len() {
            Ok(())
        } else {
            Err(BeamError::NoSuchNode {
                node: n,
                count: self.nodes.len(),
            })
        }
    }

    fn check_element(&self, e: usize) -> Result<(), BeamError> {
        if e < self.elements.len() {
            Ok(())
        } else {
            Err(BeamError::NoSuchElement {
                element: e,
                count: self.elements.len(),
            })
        }
    }

    fn check_nonempty(&self) -> Result<(), BeamError> {
        if self.elements.is_empty() {
            Err(BeamError::NoElements)
        } else {
            Ok(())
        }
    }

    /// Free/constrained DOF partition. Errors when the model has no elements or no free DOF.
    pub fn dof_map(&self) -> Result<DofMap, BeamError> {
        self.check_nonempty()?;
        let mut free = Vec::new();
        let mut constrained = Vec::new();
        let mut free_index = vec![None; self.n_dof()];
        for (d, p) in self.prescribed.iter().enumerate() {
            if p.is_some() {
                constrained.push(d);
            } else {
                free_index[d] = Some(free.len());
                free.push(d);
            }
        }
        if free.is_empty() {
            return Err(BeamError::NoFreeDof);
        }
        Ok(DofMap {
            free,
            constrained,
            free_index,
        })
    }

    fn assemble_dense(&self, f: impl Fn(&FrameElement) -> Mat6) -> Mat<f64> {
        let n = self.n_dof();
        let mut k = Mat::<f64>::zeros(n, n);
        for e in &self.elements {
            let ke = f(e);
            let d = e.dofs();
            for i in 0..6 {
                for j in 0..6 {
                    k[(d[i], d[j])] += ke[(i, j)];
                }
            }
        }
        k
    }

    fn assemble_sparse(
        &self,
        f: impl Fn(&FrameElement) -> Mat6,
    ) -> Result<SparseColMat<usize, f64>, BeamError> {
        let index: Vec<Option<usize>> = (0..self.n_dof()).map(Some).collect();
        self.assemble_sparse_on(f, &index, self.n_dof())
    }

    /// Sparse assembly onto the DOF subset given by `index` (full DOF → row/column, `None` =
    /// dropped), of dimension `dim`. Cost and storage linear in the number of elements.
    fn assemble_sparse_on(
        &self,
        f: impl Fn(&FrameElement) -> Mat6,
        index: &[Option<usize>],
        dim: usize,
    ) -> Result<SparseColMat<usize, f64>, BeamError> {
        let mut t = Vec::with_capacity(36 * self.elements.len());
        for e in &self.elements {
            let ke = f(e);
            let d = e.dofs();
            for i in 0..6 {
                for j in 0..6 {
                    if let (Some(r), Some(c)) = (index[d[i]], index[d[j]]) {
                        t.push(Triplet::new(r, c, ke[(i, j)]));
                    }
                }
            }
        }
        SparseColMat::try_new_from_triplets(dim, dim, &t)
            .map_err(|e| BeamError::Sparse(format!("{e:?}")))
    }

    /// Sparse stiffness and mass restricted to the free DOF of `map` (free ordering).
    pub fn free_sparse(&self, map: &DofMap) -> Result<(SparseMatrix, SparseMatrix), BeamError> {
        self.check_nonempty()?;
        let n = map.free.len();
        Ok((
            self.assemble_sparse_on(FrameElement::global_stiffness, &map.free_index, n)?,
            self.assemble_sparse_on(|e| e.global_mass(self.mass_kind), &map.free_index, n)?,
        ))
    }

    /// Dense global stiffness (elastic + geometric), full DOF (N/m, N, N·m).
    pub fn stiffness_dense(&self) -> Result<Mat<f64>, BeamError> {
        self.check_nonempty()?;
        Ok(self.assemble_dense(FrameElement::global_stiffness))
    }

    /// Dense global mass (kg, kg·m, kg·m²), full DOF.
    pub fn mass_dense(&self) -> Result<Mat<f64>, BeamError> {
        self.check_nonempty()?;
        Ok(self.assemble_dense(|e| e.global_mass(self.mass_kind)))
    }

    /// Dense consistent (translational) mass ∫ρA NᵀN, whatever the chosen mass kind; used for
    /// the floating-frame invariants.
    pub fn consistent_mass_dense(&self) -> Result<Mat<f64>, BeamError> {
        self.check_nonempty()?;
        Ok(self.assemble_dense(|e| e.global_mass(MassKind::Consistent)))
    }

    /// Dense Rayleigh damping α M + β K, full DOF.
    pub fn damping_dense(&self) -> Result<Mat<f64>, BeamError> {
        let (a, b) = self.rayleigh;
        Ok(self.mass_dense()? * faer::Scale(a) + self.stiffness_dense()? * faer::Scale(b))
    }

    /// Sparse (CSC) global stiffness, full DOF; cost and storage linear in the element count.
    pub fn stiffness_sparse(&self) -> Result<SparseColMat<usize, f64>, BeamError> {
        self.check_nonempty()?;
        self.assemble_sparse(FrameElement::global_stiffness)
    }

    /// Sparse (CSC) global mass, full DOF.
    pub fn mass_sparse(&self) -> Result<SparseColMat<usize, f64>, BeamError> {
        self.check_nonempty()?;
        self.assemble_sparse(|e| e.global_mass(self.mass_kind))
    }

    /// Static solution K u = f for the given loads, with prescribed displacements. Returns
    /// displacements and support reactions r = K u − f at the constrained DOF. Errors with
    /// [`BeamError::SingularStiffness`] when the supports leave a mechanism.
    pub fn solve_static(&self, loads: &Loads) -> Result<StaticSolution, BeamError> {
        let map = self.dof_map()?;
        let f = loads.vector(self)?;
        let k = self.stiffness_dense()?;
        let kff = restrict(k.as_ref(), &map.free, &map.free);
        let nf = map.free.len();
        let mut rhs = Mat::<f64>::zeros(nf, 1);
        let up: Vec<f64> = map
            .constrained
            .iter()
            .map(|&d| self.prescribed[d].unwrap_or(0.0))
            .collect();
        for (i, &di) in map.free.iter().enumerate() {
            let mut v = f[di];
            for (j, &dj) in map.constrained.iter().enumerate() {
                v -= k[(di, dj)] * up[j];
            }
            rhs[(i, 0)] = v;
        }
        let llt = checked_cholesky(kff.as_ref(), &map.free)?;
        llt.solve_in_place(rhs.as_mut());
        let mut u = vec![0.0; self.n_dof()];
        for (i, &d) in map.free.iter().enumerate() {
            u[d] = rhs[(i, 0)];
        }
        for (j, &d) in map.constrained.iter().enumerate() {
            u[d] = up[j];
        }
        let mut r = vec![0.0; self.n_dof()];
        for &d in &map.constrained {
            let ku: f64 = (0..self.n_dof()).map(|j| k[(d, j)] * u[j]).sum();
            r[d] = ku - f[d];
        }
        Ok(StaticSolution {
            displacements: u,
            reactions: r,
        })
    }
}

/// Material and section re-checked (their fields are public, so they may have been edited).
fn validated(material: Material, section: Section) -> Result<(Material, Section), BeamError> {
    Ok((
        Material::new(
            material.youngs_modulus,
            material.density,
            material.poisson_ratio,
        )?,
        Section::new(section.area, section.second_moment, section.depth)?,
    ))
}

/// Sub-matrix A[rows, cols].
pub(crate) fn restrict(a: MatRef<'_, f64>, rows: &[usize], cols: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), cols.len(), |i, j| a[(rows[i], cols[j])])
}

/// Cholesky factor of a symmetric matrix that must be positive definite; a pivot below
/// 1e-11 × its diagonal entry (or a failed factorization) is reported as a singular stiffness
/// at the corresponding full DOF `dofs[i]`.
pub(crate) fn checked_cholesky(
    a: MatRef<'_, f64>,
    dofs: &[usize],
) -> Result<faer::linalg::solvers::Llt<f64>, BeamError> {
    let n = a.nrows();
    let llt = a.llt(Side::Lower).map_err(|e| {
        let i = match e {
            faer::linalg::solvers::LltError::NonPositivePivot { index } => index.min(n - 1),
        };
        BeamError::SingularStiffness { dof: dofs[i] }
    })?;
    let l = llt.L();
    for i in 0..n {
        let d = a[(i, i)].abs();
        let pivot = l[(i, i)] * l[(i, i)];
        if pivot.is_nan() || pivot <= 1e-11 * d {
            return Err(BeamError::SingularStiffness { dof: dofs[i] });
        }
    }
    Ok(llt)
}
