//! Where a scroll may come to rest: on items, on pages, anywhere.

use crate::bounds::Bounds;
use crate::error::{Bound, Error, Parameter};
use crate::input::check_position;
use crate::scalar::Scalar;

/// The points a [`Scroll`](crate::Scroll) rests on: every multiple of a spacing (items of
/// one height, pages), the points of a slice (items of different heights), or anywhere.
///
/// At a release the scroll moves the resting point of the throw to the snap point nearest
/// to it (Motion's `modifyTarget`, iOS's `targetContentOffset`) and springs there keeping
/// its velocity; a knob's detent steps move it from one snap point to the next. A snap
/// point beyond the scroll's [`Bounds`] rests on the bound instead, so that both ends of
/// a list stay reachable.
///
/// ```
/// use stiffspring::{Bounds, Snap};
///
/// let rows = Snap::<f32>::spacing(24.0, 0.0)?; // a row every 24 px
/// let bounds = Bounds::new(0.0, 1000.0)?;
/// assert_eq!(rows.nearest(130.0, &bounds), Some(120.0));
/// assert_eq!(rows.nearest(998.0, &bounds), Some(1000.0)); // 1,008 is past the end
///
/// const STOPS: [f32; 3] = [0.0, 40.0, 200.0];
/// let stops = Snap::points(&STOPS)?;
/// assert_eq!(stops.nearest(150.0, &bounds), Some(200.0));
/// assert_eq!(Snap::<f32>::NONE.nearest(150.0, &bounds), None);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Snap<'a, S: Scalar> {
    kind: Kind<'a, S>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum Kind<'a, S: Scalar> {
    None,
    Spacing { spacing: S, origin: S },
    Points(&'a [S]),
}

impl<'a, S: Scalar> Snap<'a, S> {
    /// No snap points: a throw rests where friction stops it.
    ///
    /// ```
    /// use stiffspring::{Bounds, Snap};
    /// assert_eq!(Snap::<f32>::NONE.nearest(3.0, &Bounds::new(0.0, 9.0)?), None);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const NONE: Self = Snap { kind: Kind::None };

    /// A snap point every `spacing` from `origin` (`origin + k·spacing` for every integer
    /// `k`): rows of one height, pages of one width.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] with [`Parameter::SnapSpacing`] or [`Parameter::Position`]
    /// (the origin) for NaN or infinity; [`Error::OutOfRange`] with
    /// [`Parameter::SnapSpacing`] for a spacing `≤ 0`, or either beyond [`Scalar::MAX`].
    ///
    /// ```
    /// use stiffspring::{Error, Parameter, Snap};
    /// assert!(Snap::<f32>::spacing(0.0, 0.0).is_err());
    /// assert_eq!(
    ///     Snap::<f32>::spacing(f32::NAN, 0.0),
    ///     Err(Error::NotFinite { parameter: Parameter::SnapSpacing })
    /// );
    /// ```
    pub fn spacing(spacing: S, origin: S) -> Result<Self, Error> {
        let spacing = check_position(spacing, Parameter::SnapSpacing)?;
        let origin = check_position(origin, Parameter::Position)?;
        if spacing <= S::ZERO {
            return Err(Error::OutOfRange {
                parameter: Parameter::SnapSpacing,
                value: spacing.to_f64(),
                bound: Bound::Positive,
            });
        }
        Ok(Snap {
            kind: Kind::Spacing { spacing, origin },
        })
    }

    /// The points of `points`, in ascending order (equal neighbours are allowed); an
    /// empty slice snaps nowhere.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] (`Bound::MagnitudeAtMost`) with
    /// [`Parameter::SnapPoints`] for a point that is not a position; [`Error::OutOfRange`]
    /// with [`Parameter::SnapPoints`] and `Bound::AtLeast` the point before, for a point
    /// out of order.
    ///
    /// ```
    /// use stiffspring::{Bound, Error, Parameter, Snap};
    /// assert_eq!(
    ///     Snap::<f32>::points(&[0.0, 50.0, 20.0]),
    ///     Err(Error::OutOfRange {
    ///         parameter: Parameter::SnapPoints,
    ///         value: 20.0,
    ///         bound: Bound::AtLeast { min: 50.0 }
    ///     })
    /// );
    /// ```
    pub fn points(points: &'a [S]) -> Result<Self, Error> {
        for (i, &p) in points.iter().enumerate() {
            check_position(p, Parameter::SnapPoints)?;
            if i > 0 && p < points[i - 1] {
                return Err(Error::OutOfRange {
                    parameter: Parameter::SnapPoints,
                    value: p.to_f64(),
                    bound: Bound::AtLeast {
                        min: points[i - 1].to_f64(),
                    },
                });
            }
        }
        Ok(Snap {
            kind: Kind::Points(points),
        })
    }

    /// True when there are snap points.
    ///
    /// ```
    /// use stiffspring::Snap;
    /// assert!(!Snap::<f32>::NONE.snaps() && Snap::<f32>::spacing(8.0, 0.0)?.snaps());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn snaps(&self) -> bool {
        match self.kind {
            Kind::None => false,
            Kind::Spacing { .. } => true,
            Kind::Points(p) => !p.is_empty(),
        }
    }

    /// The snap point nearest to `position`, limited to `bounds`; `None` without snap
    /// points. A tie goes to the larger point.
    ///
    /// ```
    /// use stiffspring::{Bounds, Snap};
    /// let pages = Snap::<f64>::spacing(240.0, 0.0)?;
    /// assert_eq!(pages.nearest(130.0, &Bounds::new(0.0, 960.0)?), Some(240.0));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn nearest(&self, position: S, bounds: &Bounds<S>) -> Option<S> {
        let index = self.index_near(position.to_f64())?;
        self.point(index, bounds)
    }

    /// The snap point `steps` points after the one nearest to `from` (before, for a
    /// negative `steps`), limited to `bounds`, and how many steps there are from there to
    /// either end (`(−first, last)`, so that `steps` stopped short when it lies outside).
    /// `None` without snap points.
    pub(crate) fn step(&self, from: S, steps: i32, bounds: &Bounds<S>) -> Option<(S, (i64, i64))> {
        let (lo, hi) = self.index_range(bounds)?;
        // The point `from` is on: an end of the bounds is the first or last index.
        let at = if from <= bounds.min() {
            lo
        } else if from >= bounds.max() {
            hi
        } else {
            self.index_near(from.to_f64())?.clamp(lo, hi)
        };
        let to = at.saturating_add(i64::from(steps)).clamp(lo, hi);
        Some((self.point(to, bounds)?, (lo - at, hi - at)))
    }

    /// The index of the snap point nearest to `x` (spacing: the multiple; points: the slot).
    fn index_near(&self, x: f64) -> Option<i64> {
        match self.kind {
            Kind::None => None,
            Kind::Spacing { spacing, origin } => {
                let k = libm::floor((x - origin.to_f64()) / spacing.to_f64() + 0.5);
                Some(saturating_index(k))
            }
            Kind::Points(points) => {
                // The first point at or above x, then the nearer of it and the one before.
                let above = points.partition_point(|p| p.to_f64() < x);
                if points.is_empty() {
                    None
                } else if above == 0 {
                    Some(0)
                } else if above == points.len() {
                    Some(points.len() as i64 - 1)
                } else {
                    let (a, b) = (points[above - 1].to_f64(), points[above].to_f64());
                    Some(if x - a < b - x {
                        above as i64 - 1
                    } else {
                        above as i64
                    })
                }
            }
        }
    }

    /// The indices whose points, limited to `bounds`, are the distinct resting points:
    /// for a spacing, from the multiple at or below the minimum to the one at or above the
    /// maximum.
    fn index_range(&self, bounds: &Bounds<S>) -> Option<(i64, i64)> {
        match self.kind {
            Kind::None => None,
            Kind::Spacing { spacing, origin } => {
                let (s, o) = (spacing.to_f64(), origin.to_f64());
                let lo = libm::floor((bounds.min().to_f64() - o) / s);
                let hi = libm::ceil((bounds.max().to_f64() - o) / s);
                Some((saturating_index(lo), saturating_index(hi)))
            }
            Kind::Points(points) => (!points.is_empty()).then(|| (0, points.len() as i64 - 1)),
        }
    }

    /// Snap point `index`, limited to `bounds`.
    fn point(&self, index: i64, bounds: &Bounds<S>) -> Option<S> {
        let p = match self.kind {
            Kind::None => return None,
            // One rounding: `origin + k·spacing` is exact in f64 for the f32 and I16F16
            // positions of a list, then rounds once to `S`.
            Kind::Spacing { spacing, origin } => {
                S::from_f64(origin.to_f64() + index as f64 * spacing.to_f64())
            }
            Kind::Points(points) => *points.get(usize::try_from(index).ok()?)?,
        };
        Some(bounds.clamp(p))
    }
}

/// An index from `f64`, saturated (NaN becomes 0), far beyond any list.
fn saturating_index(k: f64) -> i64 {
    const LIMIT: f64 = (1u64 << 53) as f64;
    if k.is_nan() {
        0
    } else if k > LIMIT {
        LIMIT as i64
    } else if k < -LIMIT {
        -(LIMIT as i64)
    } else {
        k as i64
    }
}
