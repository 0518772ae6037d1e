//! The network stability measurements: topologies (ropes, meshes, mass profiles,
//! pinning), the share count the scene uses, the **linearised step matrix** of a network
//! about its rest state for either stepper, and its eigenvalues (nalgebra's real Schur
//! form).
//!
//! Nothing here uses the library: the step matrix is written from the position-level
//! impulse of the seed article (eq. 27 and 28 with the step velocity `u = v·dt` and the
//! weights `w_a = m_b/(m_a + m_b)`, `w_b = 1 − w_a` of the two bodies),
//!
//! ```text
//! δ = −(C_k·x + C_d·u_rel)     u_a −= w_a·δ·n     u_b += w_b·δ·n     (then x_i += u_i)
//! ```
//!
//! linearised about the rest configuration (every spring at its rest length, every
//! particle still). There `δ = 0`, so the rotation of the axis `n` contributes nothing to
//! first order: `x ≈ n₀·(p_b − p_a)`, `u_rel = n₀·(u_b − u_a)`, and each spring is the
//! rank-one map `u ← u + g·(−C_k·j·p − C_d·j·u)` with `j = (−n₀ at a, +n₀ at b)` and
//! `g = (−w_a·n₀ at a, +w_b·n₀ at b)`. Gauss-Seidel applies these one after the other, in
//! the library's order (springs with a pinned end first, then the others, each in
//! insertion order); Jacobi sums them all from the same state. Pinned particles never
//! move, so they are not part of the state.
//!
//! Free networks have neutral modes: translation, rotation, the floppy mechanisms of a
//! mesh without diagonals, the transverse sway of a straight rope. Their positions and
//! step velocities are null vectors of every spring's `j`, so no spring acts on them and
//! the step is `p ← p + u` there: 2×2 Jordan blocks at exactly `λ = 1` (a constant
//! drift), not instabilities. A dense eigenvalue solver resolves a Jordan block only to
//! about `√(ε·κ)`, which for a long rope with a 1:100 mass gradient is a few `10⁻⁶`
//! (above 1 as often as below), so the neutral subspace is not looked for among the
//! computed eigenvalues: it is known exactly, and [`Topology::growth_rate`] projects it
//! out before solving (see there).

use crate::rng::Rng;

use nalgebra::linalg::{Schur, balancing};

/// A dense real matrix.
pub type Matrix = nalgebra::DMatrix<f64>;

/// A complex eigenvalue.
pub type Complex = nalgebra::Complex<f64>;

/// Deflation tolerances of the Schur iteration, tried in turn (relative to the
/// neighbouring diagonal entries), each for at most `100·n` sweeps.
///
/// nalgebra's default is one machine epsilon and no iteration limit, with which its
/// Francis iteration (it has no exceptional shifts) cycled for ever on some of these step
/// matrices, whose eigenvalues crowd the unit circle: a free 3-particle rope under Jacobi
/// at `C = 1`, a 3×3 mesh with diagonals at `C = 1.5`. 1e−14 (45 ulp) converges on all of
/// the tests' matrices; a deflated entry that small moves a well-conditioned eigenvalue
/// by as much, far below the tests' tolerances (1e−9, and [`NEUTRAL`]).
pub const DEFLATION: [f64; 3] = [1e-14, 1e-12, 1e-10];

/// The eigenvalues of a real square matrix, complex ones in conjugate pairs.
///
/// The matrix is balanced (a diagonal similarity that equalises the norms of rows and
/// columns, so that couplings of very different scale, such as mass ratios of 1:100, do
/// not cost accuracy), then reduced to real Schur form by nalgebra at the [`DEFLATION`]
/// tolerances; the eigenvalues are read from its 1×1 and 2×2 diagonal blocks. When the
/// iteration still stalls (2 of the 1 680 matrices the network-limit sweep builds for a
/// 9×9 mesh and a hanging 10×10 one), it is run again on `PᵀAP` for a seeded random
/// permutation `P`: the same eigenvalues exactly, the same scales (a random orthogonal
/// similarity also unsticks it, but mixes the scales that balancing equalises), and
/// another path for the shifts.
///
/// A Jordan block (the neutral drift modes of a network) comes out perturbed by up to
/// `√(ε·κ)`: use [`Topology::growth_rate`], which removes them first, for a network's
/// stability. (faer 0.24, tried as well, hung on an 80×80 matrix of a free 20-particle
/// rope under Jacobi that nalgebra solves at once.)
///
/// # Panics
///
/// When none of three permutations converges either; the panic names the size.
pub fn eigenvalues(m: &Matrix) -> Vec<Complex> {
    let n = m.nrows();
    assert!(m.is_square(), "eigenvalues of a {n}×{} matrix", m.ncols());
    if n == 0 {
        return Vec::new();
    }
    let schur = |a: &Matrix| {
        let mut balanced = a.clone();
        balancing::balance_parlett_reinsch(&mut balanced);
        DEFLATION
            .iter()
            .find_map(|&eps| Schur::try_new(balanced.clone(), eps, 100 * n))
    };
    // A seeded random permutation P: PᵀAP is exact (no rounding), keeps the scales the
    // balancing equalises, and gives the Hessenberg reduction another start.
    let permuted = |seed: u64| {
        let mut rng = Rng::seeded(seed);
        let mut order: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            order.swap(i, rng.below(i + 1));
        }
        schur(&Matrix::from_fn(n, n, |i, j| m[(order[i], order[j])]))
    };
    schur(m)
        .or_else(|| (1..=3).find_map(permuted))
        .unwrap_or_else(|| panic!("the Schur iteration did not converge ({n}×{n})"))
        .complex_eigenvalues()
        .iter()
        .copied()
        .collect()
}

/// The largest `|λ|` of `m`.
pub fn spectral_radius(m: &Matrix) -> f64 {
    eigenvalues(m)
        .into_iter()
        .map(|e| e.norm())
        .fold(0.0, f64::max)
}

/// How far above 1 the largest `|λ|` may come out and still count as marginal rather
/// than growing: an undamped network's modes lie on the unit circle, and the solver
/// places them there to rounding once the neutral subspace is projected out (see
/// [`Topology::growth_rate`] and the test `undamped_networks_are_marginal_to_rounding`).
pub const NEUTRAL: f64 = 1e-6;

/// The two steppers, as in the library.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Order {
    GaussSeidel,
    Jacobi,
}

/// A network at rest in the plane: particles (inverse mass 0 = pinned) and springs at
/// their current length, in insertion order.
#[derive(Clone, Debug)]
pub struct Topology {
    pub name: String,
    pub positions: Vec<[f64; 2]>,
    pub inverse_masses: Vec<f64>,
    pub springs: Vec<(usize, usize)>,
}

/// How the masses of a rope vary along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Masses {
    Equal,
    /// 1, 100, 1, 100, ...
    Alternating(f64),
    /// Geometric from 1 to the ratio along the rope.
    Gradient(f64),
}

impl Topology {
    /// A straight rope of `n` particles, spacing 1, springs `(i, i+1)` in order, the first
    /// particle pinned if `pinned`.
    pub fn rope(n: usize, pinned: bool, masses: Masses) -> Self {
        let mut inverse_masses = Vec::new();
        for i in 0..n {
            let m = match masses {
                Masses::Equal => 1.0,
                Masses::Alternating(r) => {
                    if i % 2 == 0 {
                        1.0
                    } else {
                        r
                    }
                }
                Masses::Gradient(r) => r.powf(i as f64 / (n - 1).max(1) as f64),
            };
            inverse_masses.push(if pinned && i == 0 { 0.0 } else { 1.0 / m });
        }
        let name = format!(
            "rope {n}{}{}",
            if pinned { " pinned" } else { "" },
            match masses {
                Masses::Equal => String::new(),
                Masses::Alternating(r) => format!(" masses 1:{r} alternating"),
                Masses::Gradient(r) => format!(" masses 1→{r}"),
            }
        );
        Topology {
            name,
            positions: (0..n).map(|i| [i as f64, 0.0]).collect(),
            inverse_masses,
            springs: (0..n - 1).map(|i| (i, i + 1)).collect(),
        }
    }

    /// A `w × h` square mesh of unit masses, spacing 1, springs in the order of
    /// `crate::reference::network::mesh_2d` (right and up neighbour per particle in
    /// row-major order, then both diagonals per cell). `pin_top_row` pins the top row (a
    /// hanging jelly).
    pub fn mesh(w: usize, h: usize, diagonals: bool, pin_top_row: bool) -> Self {
        let mut positions = Vec::new();
        let mut inverse_masses = Vec::new();
        for r in 0..h {
            for c in 0..w {
                positions.push([c as f64, r as f64]);
                inverse_masses.push(if pin_top_row && r == h - 1 { 0.0 } else { 1.0 });
            }
        }
        let mut springs = Vec::new();
        for r in 0..h {
            for c in 0..w {
                let i = r * w + c;
                if c + 1 < w {
                    springs.push((i, i + 1));
                }
                if r + 1 < h {
                    springs.push((i, i + w));
                }
            }
        }
        if diagonals {
            for r in 0..h - 1 {
                for c in 0..w - 1 {
                    let i = r * w + c;
                    springs.push((i, i + w + 1));
                    springs.push((i + 1, i + w));
                }
            }
        }
        Topology {
            name: format!(
                "mesh {w}×{h}{}{}",
                if diagonals { " diag" } else { "" },
                if pin_top_row { " hanging" } else { "" }
            ),
            positions,
            inverse_masses,
            springs,
        }
    }

    pub fn is_free(&self, p: usize) -> bool {
        self.inverse_masses[p] > 0.0
    }

    /// Springs touching each particle.
    pub fn degrees(&self) -> Vec<usize> {
        let mut d = vec![0; self.positions.len()];
        for &(a, b) in &self.springs {
            d[a] += 1;
            d[b] += 1;
        }
        d
    }

    /// The scene's share count of each spring: the springs on its busiest free end.
    pub fn share_counts(&self) -> Vec<usize> {
        let d = self.degrees();
        self.springs
            .iter()
            .map(|&(a, b)| {
                [a, b]
                    .iter()
                    .filter(|&&p| self.is_free(p))
                    .map(|&p| d[p])
                    .max()
                    .unwrap_or(0)
            })
            .collect()
    }

    /// The largest share count of the network.
    pub fn share_count(&self) -> usize {
        self.share_counts().into_iter().max().unwrap_or(0)
    }

    /// Spring indices in the library's Gauss-Seidel order: springs with a pinned end
    /// first, then the others, each group in insertion order; springs between two pinned
    /// particles are never stepped.
    pub fn library_order(&self) -> Vec<usize> {
        let one_sided = (0..self.springs.len()).filter(|&s| {
            let (a, b) = self.springs[s];
            self.is_free(a) != self.is_free(b)
        });
        let two_sided = (0..self.springs.len()).filter(|&s| {
            let (a, b) = self.springs[s];
            self.is_free(a) && self.is_free(b)
        });
        one_sided.chain(two_sided).collect()
    }

    /// Index of each free particle in the state vector, `None` for pinned ones.
    fn state_index(&self) -> (Vec<Option<usize>>, usize) {
        let mut next = 0;
        let index = (0..self.positions.len())
            .map(|p| {
                self.is_free(p).then(|| {
                    next += 1;
                    next - 1
                })
            })
            .collect();
        (index, next)
    }

    /// The linearised step matrix on `(p, u)` (all free positions, then all free step
    /// velocities, two components each) with per-spring coefficients.
    pub fn step_matrix(&self, ck: &[f64], cd: &[f64], order: Order) -> Matrix {
        let (index, free) = self.state_index();
        let half = 2 * free;
        let n = 2 * half;
        // Rows of the spring stage, built by applying each spring's rank-one update to
        // the rows of an identity (Gauss-Seidel: to the running product; Jacobi: every
        // update reads the identity and writes a separate sum).
        let identity = Matrix::identity(n, n);
        let mut stage = Matrix::identity(n, n);
        let mut sum = Matrix::zeros(n, n);
        for s in self.library_order() {
            let (a, b) = self.springs[s];
            let d = [
                self.positions[b][0] - self.positions[a][0],
                self.positions[b][1] - self.positions[a][1],
            ];
            let len = d[0].hypot(d[1]);
            let axis = [d[0] / len, d[1] / len];
            let (ia, ib) = (self.inverse_masses[a], self.inverse_masses[b]);
            let (wa, wb) = (ia / (ia + ib), ib / (ia + ib));
            // j·z for the p-part and the u-part, as (state column, coefficient) pairs.
            let mut j: Vec<(usize, f64)> = Vec::new();
            let mut g: Vec<(usize, f64)> = Vec::new();
            for (end, sign, weight) in [(a, -1.0, wa), (b, 1.0, wb)] {
                if let Some(i) = index[end] {
                    for (k, n) in axis.iter().enumerate() {
                        j.push((2 * i + k, sign * n));
                        g.push((half + 2 * i + k, sign * weight * n));
                    }
                }
            }
            // δ(row) = −C_k·Σ j·P[row of p] − C_d·Σ j·P[row of u], for every column.
            let source = match order {
                Order::GaussSeidel => &stage,
                Order::Jacobi => &identity,
            };
            let mut delta = vec![0.0; n];
            for (col, dcol) in delta.iter_mut().enumerate() {
                let mut x = 0.0;
                let mut v = 0.0;
                for &(i, c) in &j {
                    x += c * source[(i, col)];
                    v += c * source[(half + i, col)];
                }
                *dcol = -ck[s] * x - cd[s] * v;
            }
            let target = match order {
                Order::GaussSeidel => &mut stage,
                Order::Jacobi => &mut sum,
            };
            for &(row, c) in &g {
                for (col, dcol) in delta.iter().enumerate() {
                    target[(row, col)] += c * dcol;
                }
            }
        }
        if order == Order::Jacobi {
            stage += &sum;
        }
        // Drift: p ← p + u (with the new u).
        let mut step = stage.clone();
        for row in 0..half {
            for col in 0..n {
                step[(row, col)] += stage[(half + row, col)];
            }
        }
        step
    }

    /// The same matrix with every spring at `(c, c)`.
    pub fn uniform_step_matrix(&self, c: f64, order: Order) -> Matrix {
        let m = self.springs.len();
        self.step_matrix(&vec![c; m], &vec![c; m], order)
    }

    /// The largest eigenvalue `μ` of `R^{½}·J·M⁻¹·Jᵀ·R^{½}` (R the reduced masses): with
    /// every spring at `(c, c)`, Jacobi's modes are single springs at `(μc, μc)`, stable
    /// exactly when `3·μ·c < 4` (Jury), so Jacobi's limit is `4/(3·μ_max)`.
    pub fn jacobi_mu_max(&self) -> f64 {
        // Nonzero eigenvalues equal those of M^{-½}·Jᵀ·R·J·M^{-½} (free particles only).
        let (index, free) = self.state_index();
        let n = 2 * free;
        let mut k = Matrix::zeros(n, n);
        for &(a, b) in &self.springs {
            let (ia, ib) = (self.inverse_masses[a], self.inverse_masses[b]);
            if ia + ib == 0.0 {
                continue;
            }
            let r = 1.0 / (ia + ib);
            let d = [
                self.positions[b][0] - self.positions[a][0],
                self.positions[b][1] - self.positions[a][1],
            ];
            let len = d[0].hypot(d[1]);
            let axis = [d[0] / len, d[1] / len];
            let mut j = Vec::new();
            for (end, sign) in [(a, -1.0), (b, 1.0)] {
                if let Some(i) = index[end] {
                    let scale = self.inverse_masses[end].sqrt();
                    for (c, n) in axis.iter().enumerate() {
                        j.push((2 * i + c, sign * n * scale));
                    }
                }
            }
            for &(r1, c1) in &j {
                for &(r2, c2) in &j {
                    k[(r1, r2)] += r * c1 * c2;
                }
            }
        }
        eigenvalues(&k)
            .into_iter()
            .map(|e| e.re)
            .fold(0.0, f64::max)
    }
}

impl Topology {
    /// The largest `|λ|` of the step with per-spring coefficients `ck`, `cd`, minus 1,
    /// over the modes that are not neutral: negative for a decaying network, about 0
    /// for a marginal (undamped) one, positive for a growing one.
    ///
    /// **The neutral subspace, exactly.** Let `J_k` be the rows `j_s` of the springs with
    /// `C_k ≠ 0`, and `J_a` those of the springs with `C_k ≠ 0` or `C_d ≠ 0`. On
    /// `N = ker J_k × ker J_a` (positions, step velocities) every spring's
    /// `δ = −(C_k·j·p + C_d·j·u)` is 0, so the spring stage (either order) is the
    /// identity and the step is `p ← p + u`, which maps `N` into itself
    /// (`C_k·j·(p + u) = 0`): every eigenvalue there is exactly 1. With orthonormal bases
    /// `[Q_N, Q]` of `N` and its complement the step is block upper triangular
    /// (`Qᵀ·A·Q_N = 0`), so the other eigenvalues are exactly those of `Qᵀ·A·Q`, whose
    /// Jordan blocks at 1 are gone. `Q` is `R_k ⊕ R_a`, the row spaces of `J_k` and `J_a`
    /// from their singular value decompositions (`j` holds unit axes, independent of the
    /// masses: its rank is clear-cut, singular values below `10⁻¹⁰` of the largest are
    /// taken as zero).
    pub fn growth_rate(&self, ck: &[f64], cd: &[f64], order: Order) -> f64 {
        let a = self.step_matrix(ck, cd, order);
        let q = self.non_neutral_basis(ck, cd);
        if q.ncols() == 0 {
            // Nothing but neutral modes (no spring acts): marginal.
            return 0.0;
        }
        let compressed = q.transpose() * a * &q;
        spectral_radius(&compressed) - 1.0
    }

    /// The rows `j_s` in position coordinates (two per free particle, in state order) of
    /// the springs `keep` selects; a spring between two pinned particles has none.
    fn constraint_rows(&self, keep: impl Fn(usize) -> bool) -> Vec<Vec<f64>> {
        let (index, free) = self.state_index();
        let mut rows = Vec::new();
        for s in (0..self.springs.len()).filter(|&s| keep(s)) {
            let (a, b) = self.springs[s];
            let d = [
                self.positions[b][0] - self.positions[a][0],
                self.positions[b][1] - self.positions[a][1],
            ];
            let len = d[0].hypot(d[1]);
            let mut row = vec![0.0; 2 * free];
            let mut any = false;
            for (end, sign) in [(a, -1.0), (b, 1.0)] {
                if let Some(i) = index[end] {
                    row[2 * i] += sign * d[0] / len;
                    row[2 * i + 1] += sign * d[1] / len;
                    any = true;
                }
            }
            if any {
                rows.push(row);
            }
        }
        rows
    }

    /// The orthonormal basis `Q = R_k ⊕ R_a` of the complement of the neutral subspace
    /// (see [`Topology::growth_rate`]), as the columns of a matrix on the state
    /// `(p, u)`.
    pub fn non_neutral_basis(&self, ck: &[f64], cd: &[f64]) -> Matrix {
        let (_, free) = self.state_index();
        let half = 2 * free;
        let stiff = row_space(&self.constraint_rows(|s| ck[s] != 0.0), half);
        let acting = row_space(
            &self.constraint_rows(|s| ck[s] != 0.0 || cd[s] != 0.0),
            half,
        );
        let (rk, ra) = (stiff.ncols(), acting.ncols());
        let mut q = Matrix::zeros(2 * half, rk + ra);
        q.view_mut((0, 0), (half, rk)).copy_from(&stiff);
        q.view_mut((half, rk), (half, ra)).copy_from(&acting);
        q
    }
}

/// An orthonormal basis (as columns) of the span of `rows`, vectors of length `n`:
/// Gram–Schmidt with pivoting (each step takes the row with the largest part not yet
/// spanned, orthogonalised twice), stopping when what is left is below `10⁻¹⁰` of the
/// longest row. The basis is checked before it is used: orthonormal, and spanning every
/// row.
///
/// Not nalgebra's SVD: on these rank-deficient matrices (parallel springs, a collinear
/// star) it returned wrong decompositions, at its default tolerance as well as at ε (see
/// the test `parallel_springs_have_a_one_dimensional_row_space`).
///
/// # Panics
///
/// When the check fails; the panic names the size.
fn row_space(rows: &[Vec<f64>], n: usize) -> Matrix {
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let longest = rows.iter().map(|r| dot(r, r).sqrt()).fold(0.0, f64::max);
    let mut left: Vec<Vec<f64>> = rows.to_vec();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    while basis.len() < n {
        let Some((i, norm)) = left
            .iter()
            .map(|r| dot(r, r).sqrt())
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            break;
        };
        if norm <= 1e-10 * longest {
            break;
        }
        let mut q = left.swap_remove(i);
        for _ in 0..2 {
            for b in &basis {
                let c = dot(&q, b);
                q.iter_mut().zip(b).for_each(|(x, y)| *x -= c * y);
            }
        }
        let length = dot(&q, &q).sqrt();
        q.iter_mut().for_each(|x| *x /= length);
        for r in left.iter_mut() {
            let c = dot(r, &q);
            r.iter_mut().zip(&q).for_each(|(x, y)| *x -= c * y);
        }
        basis.push(q);
    }
    let q = Matrix::from_fn(n, basis.len(), |r, c| basis[c][r]);
    let j = Matrix::from_fn(rows.len(), n, |r, c| rows[r][c]);
    let identity = Matrix::identity(basis.len(), basis.len());
    let orthonormal = (q.transpose() * &q - identity).amax() < 1e-12;
    let spanning = rows.is_empty() || (&j - &j * &q * q.transpose()).amax() < 1e-9 * longest;
    assert!(
        orthonormal && spanning,
        "the row space of a {}×{n} matrix fails its check",
        rows.len()
    );
    q
}

/// The largest `c` in `(0, hi]` with every spring at `(c, c)` whose linearised step
/// matrix has no growing mode, to `tol` (bisection; `hi` itself if it is stable).
pub fn linear_limit(top: &Topology, order: Order, hi: f64, tol: f64) -> f64 {
    let unstable = |c: f64| {
        let m = top.springs.len();
        top.growth_rate(&vec![c; m], &vec![c; m], order) > NEUTRAL
    };
    if !unstable(hi) {
        return hi;
    }
    let (mut lo, mut hi) = (0.0, hi);
    while hi - lo > tol {
        let mid = 0.5 * (lo + hi);
        if unstable(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

impl Topology {
    /// One free particle of unit mass with `n` springs to pinned anchors on a line
    /// through it, alternately on either side: all `n` springs act along one axis. The
    /// worst geometry for a share count `n` (a particle between parallel springs, a
    /// folded rope), which a deforming network can approach.
    pub fn collinear_star(n: usize) -> Self {
        let mut positions = vec![[0.0, 0.0]];
        let mut inverse_masses = vec![1.0];
        let mut springs = Vec::new();
        for k in 0..n {
            positions.push([if k % 2 == 0 { 1.0 } else { -1.0 }, 0.0]);
            inverse_masses.push(0.0);
            springs.push((k + 1, 0));
        }
        Topology {
            name: format!("collinear star {n}"),
            positions,
            inverse_masses,
            springs,
        }
    }
}

/// Ratios `C_d/C_k` (and `C_k/C_d`) sampled on the outer edges of the square `[0, L]²`.
pub const EDGE_RATIOS: [f64; 14] = [
    0.0, 1e-3, 0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.75, 1.0,
];

/// True when every sampled point of the outer edges of `[0, l]²` is linearly stable.
pub fn square_is_stable(top: &Topology, order: Order, l: f64) -> bool {
    let m = top.springs.len();
    EDGE_RATIOS.iter().all(|&r| {
        [(l, r * l), (r * l, l)]
            .iter()
            .all(|&(ck, cd)| top.growth_rate(&vec![ck; m], &vec![cd; m], order) <= NEUTRAL)
    })
}

/// The largest `L ≤ hi` such that the square `[0, L]²` is stable, to `tol`.
pub fn square_limit(top: &Topology, order: Order, hi: f64, tol: f64) -> f64 {
    if square_is_stable(top, order, hi) {
        return hi;
    }
    let (mut lo, mut hi) = (0.0, hi);
    while hi - lo > tol {
        let mid = 0.5 * (lo + hi);
        if square_is_stable(top, order, mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

impl Topology {
    /// The shortest rest length.
    pub fn shortest(&self) -> f64 {
        self.springs
            .iter()
            .map(|&(a, b)| {
                let d = [
                    self.positions[b][0] - self.positions[a][0],
                    self.positions[b][1] - self.positions[a][1],
                ];
                d[0].hypot(d[1])
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Positions with every free particle moved by a random vector of each component
    /// uniform in `±fraction·shortest`: a deformation of about `fraction` (strains of up
    /// to `2·√2·fraction`).
    pub fn deformed(&self, fraction: f64, seed: u64) -> Vec<[f64; 2]> {
        let mut rng = Rng::seeded(seed);
        let scale = fraction * self.shortest();
        self.positions
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if self.is_free(i) {
                    [
                        p[0] + rng.range(-scale, scale),
                        p[1] + rng.range(-scale, scale),
                    ]
                } else {
                    *p
                }
            })
            .collect()
    }
}

impl Topology {
    /// A random network: 2 to 8 particles in the unit square (no two closer than 0.05),
    /// masses log-uniform over `mass_ratio` (a quarter pinned), 1 to 14 springs between
    /// random pairs (duplicates allowed: parallel springs are the worst geometry).
    pub fn random(rng: &mut Rng, mass_ratio: f64) -> Self {
        let k = 2 + rng.below(7);
        let mut positions: Vec<[f64; 2]> = Vec::new();
        while positions.len() < k {
            let p = [rng.unit(), rng.unit()];
            if positions
                .iter()
                .all(|q| (q[0] - p[0]).hypot(q[1] - p[1]) > 0.05)
            {
                positions.push(p);
            }
        }
        let half = mass_ratio.log10() / 2.0;
        let inverse_masses: Vec<f64> = (0..k)
            .map(|_| {
                if rng.unit() < 0.25 {
                    0.0
                } else {
                    10f64.powf(rng.range(-half, half))
                }
            })
            .collect();
        let mut springs = Vec::new();
        for _ in 0..1 + rng.below(14) {
            let a = rng.below(k);
            let b = rng.below(k);
            if a != b && (inverse_masses[a] > 0.0 || inverse_masses[b] > 0.0) {
                springs.push((a, b));
            }
        }
        if springs.is_empty() {
            // Always at least one spring with a free end.
            let free = (0..k).find(|&p| inverse_masses[p] > 0.0).unwrap_or(0);
            springs.push((free, (free + 1) % k));
        }
        let mut top = Topology {
            name: "random".into(),
            positions,
            inverse_masses,
            springs,
        };
        if top
            .springs
            .iter()
            .all(|&(a, b)| !top.is_free(a) && !top.is_free(b))
        {
            top.inverse_masses[0] = 1.0;
        }
        top
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eigenvalues_of_known_spectra() {
        // Block-diagonal 2×2 rotations-and-scalings plus real eigenvalues, hidden by a
        // similarity transform with a random (well-conditioned) matrix.
        let mut rng = Rng::seeded(99);
        for size in [2usize, 5, 9, 16, 40] {
            let mut expected = Vec::new();
            let mut d = Matrix::zeros(size, size);
            let mut i = 0;
            while i < size {
                if i + 1 < size && rng.unit() < 0.5 {
                    let (re, im) = (rng.range(-1.5, 1.5), rng.range(0.01, 1.0));
                    d[(i, i)] = re;
                    d[(i, i + 1)] = im;
                    d[(i + 1, i)] = -im;
                    d[(i + 1, i + 1)] = re;
                    expected.push(re.hypot(im));
                    expected.push(re.hypot(im));
                    i += 2;
                } else {
                    let re = rng.range(-1.5, 1.5);
                    d[(i, i)] = re;
                    expected.push(re.abs());
                    i += 1;
                }
            }
            // S = I + small random.
            let s = Matrix::from_fn(size, size, |i, j| {
                f64::from(u8::from(i == j)) + rng.range(-0.3, 0.3) / size as f64
            });
            let inv = s.clone().try_inverse().expect("well conditioned");
            let a = &s * &d * &inv;
            let mut got: Vec<f64> = eigenvalues(&a).iter().map(|e| e.norm()).collect();
            got.sort_by(f64::total_cmp);
            expected.sort_by(f64::total_cmp);
            for (g, e) in got.iter().zip(&expected) {
                assert!((g - e).abs() < 1e-9, "size {size}: {got:?} vs {expected:?}");
            }
            assert!((spectral_radius(&a) - expected[size - 1]).abs() < 1e-9);
        }
    }

    /// The matrices on which the Schur iteration stalls without a permutation.
    #[test]
    fn stalled_iterations_are_permuted() {
        for top in [
            Topology::mesh(9, 9, false, false),
            Topology::mesh(10, 10, false, true),
        ] {
            let c = if top.name.contains("hanging") {
                0.21328000000000003
            } else {
                0.31992
            };
            let m = top.springs.len();
            let a = top.step_matrix(&vec![c; m], &vec![1.0664; m], Order::GaussSeidel);
            let mut balanced = a.clone();
            balancing::balance_parlett_reinsch(&mut balanced);
            let n = a.nrows();
            let stalls = DEFLATION
                .iter()
                .all(|&eps| Schur::try_new(balanced.clone(), eps, 100 * n).is_none());
            assert!(
                stalls,
                "{}: converges now; the permutation is no longer needed for it",
                top.name
            );
            let e = eigenvalues(&a);
            assert_eq!(e.len(), n);
            assert!(e.iter().all(|z| z.re.is_finite() && z.im.is_finite()));
            // These points lie on the edge of the bisection, near marginal stability: the
            // spectral radius is 1 to a few parts per million.
            let radius = spectral_radius(&a);
            assert!((radius - 1.0).abs() < 1e-4, "{}: ρ = {radius}", top.name);
        }
    }

    #[test]
    fn a_single_spring_has_the_closed_form_spectral_radius() {
        for (ck, cd) in [
            (0.3, 0.3),
            (1.0, 1.0),
            (1.2, 1.2),
            (0.01, 0.0),
            (2.0, 0.5),
            (0.5, 1.5),
        ] {
            let top = Topology::rope(2, true, Masses::Equal);
            let radius = crate::reference::spectral_radius(ck, cd);
            for order in [Order::GaussSeidel, Order::Jacobi] {
                let growth = top.growth_rate(&[ck], &[cd], order);
                assert!((growth + 1.0 - radius).abs() < 1e-9, "({ck}, {cd})");
            }
        }
    }

    /// The dimension of the neutral subspace `N` of a topology at `(ck, cd)`.
    fn neutral_dimension(top: &Topology, ck: &[f64], cd: &[f64]) -> usize {
        let q = top.non_neutral_basis(ck, cd);
        q.nrows() - q.ncols()
    }

    /// Projecting out the neutral subspace keeps every other eigenvalue: on matrices the
    /// solver handles well, the full spectrum is the compressed one plus `dim N`
    /// eigenvalues at 1 (to the `√ε` of their Jordan blocks), and `Q` is orthonormal.
    #[test]
    fn projection_removes_exactly_the_neutral_modes() {
        let mut rng = Rng::seeded(5);
        let mut cases = vec![
            (Topology::rope(5, false, Masses::Equal), 0.4, 0.3),
            (Topology::rope(6, true, Masses::Alternating(3.0)), 0.7, 0.1),
            (Topology::mesh(3, 3, false, false), 0.3, 0.2),
            (Topology::mesh(3, 3, true, true), 0.2, 0.5),
            (Topology::collinear_star(3), 0.5, 0.0),
            (Topology::rope(4, false, Masses::Equal), 0.0, 0.6),
        ];
        for _ in 0..20 {
            cases.push((Topology::random(&mut rng, 10.0), 0.2, 0.1));
        }
        cases.push((parallel_springs(), 0.3, 0.4));
        for (top, ck, cd) in cases {
            let m = top.springs.len();
            let (ck, cd) = (vec![ck; m], vec![cd; m]);
            for order in [Order::GaussSeidel, Order::Jacobi] {
                let a = top.step_matrix(&ck, &cd, order);
                let q = top.non_neutral_basis(&ck, &cd);
                let identity = Matrix::identity(q.ncols(), q.ncols());
                assert!(
                    (q.transpose() * &q - identity).amax() < 1e-12,
                    "{}",
                    top.name
                );
                // N is invariant: with P = Q·Qᵀ the projector onto its complement,
                // P·A·(I − P) = 0.
                let p = &q * q.transpose();
                let rest = Matrix::identity(a.nrows(), a.nrows()) - &p;
                assert!((&p * &a * rest).amax() < 1e-12, "{} {order:?}", top.name);
                let neutral = neutral_dimension(&top, &ck, &cd);
                let mut all = eigenvalues(&a);
                let kept = eigenvalues(&(q.transpose() * &a * &q));
                assert_eq!(all.len(), kept.len() + neutral, "{}", top.name);
                // Match each kept eigenvalue to the nearest unused one of the full
                // spectrum; what is left must sit at 1.
                for k in &kept {
                    let (i, d) = all
                        .iter()
                        .enumerate()
                        .map(|(i, e)| (i, (e - k).norm()))
                        .min_by(|x, y| x.1.total_cmp(&y.1))
                        .expect("not empty");
                    assert!(d < 1e-6, "{} {order:?}: {k} unmatched ({d:e})", top.name);
                    all.swap_remove(i);
                }
                for e in &all {
                    assert!(
                        (e - Complex::new(1.0, 0.0)).norm() < 1e-6,
                        "{}: {e}",
                        top.name
                    );
                }
            }
        }
    }

    /// The row the full sweep failed on before the projection: a pinned 64-particle rope
    /// with masses 1 to 100 under Gauss-Seidel, where the solver put the 63 neutral modes
    /// of the rope's transverse sway 3·10⁻⁶ to 4·10⁻⁶ above 1 (at `(0.15, 0.5)` and
    /// `(0.3, 1)`, points of the square search). Projected out, the rope's axial modes
    /// all decay.
    #[test]
    fn a_graded_rope_decays_once_its_sway_is_projected_out() {
        let top = Topology::rope(64, true, Masses::Gradient(100.0));
        let m = top.springs.len();
        let mut unfiltered_growth = f64::NEG_INFINITY;
        for (ck, cd) in [(0.15, 0.5), (0.3, 1.0)] {
            let growth = top.growth_rate(&vec![ck; m], &vec![cd; m], Order::GaussSeidel);
            assert!(growth < 0.0, "({ck}, {cd}): {growth}");
            let a = top.step_matrix(&vec![ck; m], &vec![cd; m], Order::GaussSeidel);
            unfiltered_growth = unfiltered_growth.max(spectral_radius(&a) - 1.0);
        }
        // Without it, a neutral mode comes out beyond NEUTRAL: the reason for it.
        assert!(unfiltered_growth > NEUTRAL, "{unfiltered_growth}");
    }

    /// Undamped networks are marginal: their modes lie on the unit circle, and with the
    /// neutral subspace projected out the solver puts them there to rounding, far within
    /// [`NEUTRAL`].
    #[test]
    fn undamped_networks_are_marginal_to_rounding() {
        let mut worst: f64 = 0.0;
        for top in [
            Topology::rope(16, false, Masses::Equal),
            Topology::rope(64, true, Masses::Gradient(100.0)),
            Topology::rope(32, true, Masses::Alternating(100.0)),
            Topology::mesh(6, 6, true, false),
            Topology::mesh(6, 6, false, true),
        ] {
            let m = top.springs.len();
            for order in [Order::GaussSeidel, Order::Jacobi] {
                for c in [0.01, 0.1, 0.3] {
                    let growth = top.growth_rate(&vec![c; m], &vec![0.0; m], order);
                    worst = worst.max(growth.abs());
                }
            }
        }
        println!("undamped: largest ||λ| − 1| {worst:.1e}");
        assert!(worst < 5e-13, "{worst:e}");
    }

    /// Two free particles (masses 1:7600) joined by three parallel springs, one of them
    /// the way round: a random network of the flutter test.
    fn parallel_springs() -> Topology {
        Topology {
            name: "parallel springs".into(),
            positions: vec![
                [0.9286685468902699, 0.4378997826581892],
                [0.30168943771479884, 0.15077649062252574],
            ],
            inverse_masses: vec![0.02124520201393679, 161.954380378945],
            springs: vec![(0, 1), (1, 0), (1, 0)],
        }
    }

    /// Three parallel springs have one row `j` between them: a one-dimensional row space
    /// along it. (nalgebra's SVD got this wrong; `row_space` does not use it.)
    #[test]
    fn parallel_springs_have_a_one_dimensional_row_space() {
        let top = parallel_springs();
        let rows = top.constraint_rows(|_| true);
        let q = row_space(&rows, 4);
        assert_eq!(q.ncols(), 1);
        let r = &rows[0];
        let norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        let along: f64 = (0..4).map(|i| q[(i, 0)] * r[i] / norm).sum();
        assert!((along.abs() - 1.0).abs() < 1e-12, "{along}");
        // The bug this avoids: nalgebra's SVD of these rows is wrong (√14 instead of √6).
        let j = Matrix::from_fn(3, 4, |i, c| rows[i][c]);
        let svd =
            nalgebra::linalg::SVD::try_new(j, false, true, f64::EPSILON, 0).expect("converges");
        assert!(
            (svd.singular_values.max() - 6f64.sqrt()).abs() > 1.0,
            "nalgebra's SVD is right again: {:?}",
            svd.singular_values.as_slice()
        );
    }
}
