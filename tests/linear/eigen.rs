//! Eigenvalues of a dense real matrix: balancing, reduction to upper Hessenberg form by
//! stabilised elementary similarity transforms, and the Francis double-shift QR
//! iteration (the classic EISPACK `balanc`/`elmhes`/`hqr` sequence, as in Numerical
//! Recipes §11.5–11.6), written out here so the stress tests need no linear-algebra
//! dependency. Eigenvalues only, no vectors: that is all a spectral radius needs.
//!
//! Indices run from 1 internally (row and column 0 are unused), as in the published
//! algorithms, so the code can be checked line by line against them; hence the index
//! loops.
#![allow(clippy::needless_range_loop)]

/// A dense square matrix, row-major.
#[derive(Clone, Debug)]
pub struct Matrix {
    pub n: usize,
    pub data: Vec<f64>,
}

impl Matrix {
    pub fn zeros(n: usize) -> Self {
        Matrix {
            n,
            data: vec![0.0; n * n],
        }
    }

    pub fn identity(n: usize) -> Self {
        let mut m = Matrix::zeros(n);
        for i in 0..n {
            m.data[i * n + i] = 1.0;
        }
        m
    }

    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.data[i * self.n + j]
    }

    pub fn at_mut(&mut self, i: usize, j: usize) -> &mut f64 {
        &mut self.data[i * self.n + j]
    }

    pub fn mul(&self, other: &Matrix) -> Matrix {
        let n = self.n;
        let mut out = Matrix::zeros(n);
        for i in 0..n {
            for k in 0..n {
                let a = self.at(i, k);
                if a != 0.0 {
                    for j in 0..n {
                        out.data[i * n + j] += a * other.data[k * n + j];
                    }
                }
            }
        }
        out
    }

    pub fn apply(&self, v: &[f64]) -> Vec<f64> {
        (0..self.n)
            .map(|i| (0..self.n).map(|j| self.at(i, j) * v[j]).sum())
            .collect()
    }
}

/// A complex eigenvalue `re + i·im`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eigenvalue {
    pub re: f64,
    pub im: f64,
}

impl Eigenvalue {
    pub fn modulus(self) -> f64 {
        self.re.hypot(self.im)
    }
}

/// All eigenvalues of `m`.
pub fn eigenvalues(m: &Matrix) -> Vec<Eigenvalue> {
    let n = m.n;
    // 1-based copy.
    let mut a = vec![vec![0.0f64; n + 1]; n + 1];
    for i in 0..n {
        for j in 0..n {
            a[i + 1][j + 1] = m.at(i, j);
        }
    }
    balance(&mut a, n);
    hessenberg(&mut a, n);
    hqr(&mut a, n)
}

/// The largest modulus of the eigenvalues of `m`.
pub fn spectral_radius(m: &Matrix) -> f64 {
    eigenvalues(m)
        .into_iter()
        .map(Eigenvalue::modulus)
        .fold(0.0, f64::max)
}

const RADIX: f64 = 2.0;

/// Scales rows and columns by powers of 2 so that their norms are comparable (exact
/// similarity transforms: no rounding).
fn balance(a: &mut [Vec<f64>], n: usize) {
    let sqrdx = RADIX * RADIX;
    let mut done = false;
    while !done {
        done = true;
        for i in 1..=n {
            let (mut r, mut c) = (0.0, 0.0);
            for j in 1..=n {
                if j != i {
                    c += a[j][i].abs();
                    r += a[i][j].abs();
                }
            }
            if c != 0.0 && r != 0.0 {
                let mut g = r / RADIX;
                let mut f = 1.0;
                let s = c + r;
                while c < g {
                    f *= RADIX;
                    c *= sqrdx;
                }
                g = r * RADIX;
                while c > g {
                    f /= RADIX;
                    c /= sqrdx;
                }
                if (c + r) / f < 0.95 * s {
                    done = false;
                    let g = 1.0 / f;
                    for j in 1..=n {
                        a[i][j] *= g;
                    }
                    for j in 1..=n {
                        a[j][i] *= f;
                    }
                }
            }
        }
    }
}

/// Reduction to upper Hessenberg form by Gaussian elimination with pivoting.
fn hessenberg(a: &mut [Vec<f64>], n: usize) {
    for m in 2..n {
        let mut x: f64 = 0.0;
        let mut i = m;
        for j in m..=n {
            if a[j][m - 1].abs() > x.abs() {
                x = a[j][m - 1];
                i = j;
            }
        }
        if i != m {
            for j in (m - 1)..=n {
                let t = a[i][j];
                a[i][j] = a[m][j];
                a[m][j] = t;
            }
            for row in a.iter_mut().take(n + 1).skip(1) {
                row.swap(i, m);
            }
        }
        if x != 0.0 {
            for i in (m + 1)..=n {
                let mut y = a[i][m - 1];
                if y != 0.0 {
                    y /= x;
                    a[i][m - 1] = y;
                    for j in m..=n {
                        a[i][j] -= y * a[m][j];
                    }
                    for j in 1..=n {
                        a[j][m] += y * a[j][i];
                    }
                }
            }
        }
    }
}

fn sign(a: f64, b: f64) -> f64 {
    if b >= 0.0 { a.abs() } else { -a.abs() }
}

/// Francis double-shift QR on an upper Hessenberg matrix.
#[allow(clippy::many_single_char_names)]
fn hqr(a: &mut [Vec<f64>], n: usize) -> Vec<Eigenvalue> {
    let mut wr = vec![0.0; n + 1];
    let mut wi = vec![0.0; n + 1];
    let mut anorm = 0.0;
    for i in 1..=n {
        for j in i.saturating_sub(1).max(1)..=n {
            anorm += a[i][j].abs();
        }
    }
    let mut nn = n as isize;
    let mut t = 0.0;
    let mut p: f64;
    let mut q: f64;
    let mut r: f64;
    let (mut x, mut y, mut z);
    let mut w;
    while nn >= 1 {
        let mut its = 0;
        loop {
            let nu = nn as usize;
            // Look for a single small subdiagonal element.
            let mut l = nu;
            while l >= 2 {
                let mut s = a[l - 1][l - 1].abs() + a[l][l].abs();
                if s == 0.0 {
                    s = anorm;
                }
                if a[l][l - 1].abs() + s == s {
                    a[l][l - 1] = 0.0;
                    break;
                }
                l -= 1;
            }
            x = a[nu][nu];
            if l == nu {
                // One root found.
                wr[nu] = x + t;
                wi[nu] = 0.0;
                nn -= 1;
            } else {
                y = a[nu - 1][nu - 1];
                w = a[nu][nu - 1] * a[nu - 1][nu];
                if l == nu - 1 {
                    // Two roots found.
                    p = 0.5 * (y - x);
                    q = p * p + w;
                    z = q.abs().sqrt();
                    x += t;
                    if q >= 0.0 {
                        z = p + sign(z, p);
                        wr[nu - 1] = x + z;
                        wr[nu] = x + z;
                        if z != 0.0 {
                            wr[nu] = x - w / z;
                        }
                        wi[nu - 1] = 0.0;
                        wi[nu] = 0.0;
                    } else {
                        wr[nu - 1] = x + p;
                        wr[nu] = x + p;
                        wi[nu - 1] = -z;
                        wi[nu] = z;
                    }
                    nn -= 2;
                } else {
                    assert!(its < 300, "hqr: no convergence");
                    if its > 0 && its % 10 == 0 {
                        // Exceptional shift.
                        t += x;
                        for i in 1..=nu {
                            a[i][i] -= x;
                        }
                        let s = a[nu][nu - 1].abs() + a[nu - 1][nu - 2].abs();
                        x = 0.75 * s;
                        y = x;
                        w = -0.4375 * s * s;
                    }
                    its += 1;
                    // Form the shift and look for two consecutive small subdiagonals.
                    let mut m = nu - 2;
                    loop {
                        z = a[m][m];
                        r = x - z;
                        let s0 = y - z;
                        p = (r * s0 - w) / a[m + 1][m] + a[m][m + 1];
                        q = a[m + 1][m + 1] - z - r - s0;
                        r = a[m + 2][m + 1];
                        let s = p.abs() + q.abs() + r.abs();
                        p /= s;
                        q /= s;
                        r /= s;
                        if m == l {
                            break;
                        }
                        let u = a[m][m - 1].abs() * (q.abs() + r.abs());
                        let v = p.abs() * (a[m - 1][m - 1].abs() + z.abs() + a[m + 1][m + 1].abs());
                        if u + v == v {
                            break;
                        }
                        m -= 1;
                    }
                    for i in (m + 2)..=nu {
                        a[i][i - 2] = 0.0;
                        if i != m + 2 {
                            a[i][i - 3] = 0.0;
                        }
                    }
                    // The double QR step on rows l..nn and columns m..nn.
                    let mut k = m;
                    while k < nu {
                        if k != m {
                            p = a[k][k - 1];
                            q = a[k + 1][k - 1];
                            r = 0.0;
                            if k != nu - 1 {
                                r = a[k + 2][k - 1];
                            }
                            x = p.abs() + q.abs() + r.abs();
                            if x != 0.0 {
                                p /= x;
                                q /= x;
                                r /= x;
                            }
                        }
                        let s = sign((p * p + q * q + r * r).sqrt(), p);
                        if s != 0.0 {
                            if k == m {
                                if l != m {
                                    a[k][k - 1] = -a[k][k - 1];
                                }
                            } else {
                                a[k][k - 1] = -s * x;
                            }
                            p += s;
                            x = p / s;
                            y = q / s;
                            z = r / s;
                            q /= p;
                            r /= p;
                            for j in k..=nu {
                                p = a[k][j] + q * a[k + 1][j];
                                if k != nu - 1 {
                                    p += r * a[k + 2][j];
                                    a[k + 2][j] -= p * z;
                                }
                                a[k + 1][j] -= p * y;
                                a[k][j] -= p * x;
                            }
                            let mmin = if nu < k + 3 { nu } else { k + 3 };
                            for i in l..=mmin {
                                p = x * a[i][k] + y * a[i][k + 1];
                                if k != nu - 1 {
                                    p += z * a[i][k + 2];
                                    a[i][k + 2] -= p * r;
                                }
                                a[i][k + 1] -= p * q;
                                a[i][k] -= p;
                            }
                        }
                        k += 1;
                    }
                }
            }
            if nn < 1 || l as isize >= nn - 1 {
                break;
            }
        }
    }
    (1..=n)
        .map(|i| Eigenvalue {
            re: wr[i],
            im: wi[i],
        })
        .collect()
}
