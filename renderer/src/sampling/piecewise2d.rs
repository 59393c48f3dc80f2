//! A piecewise-constant density on the unit square: `nu × nv` cells of non-negative weights,
//! sampled by row (the marginal) and then by column within the row (the conditional), as in
//! pbrt-v4's `PiecewiseConstant2D`. The environment map warps it onto the sphere.

use super::DiscreteDistribution;
use glam::Vec2;

/// Cells are indexed `[row * nu + column]`; `x` runs along columns, `y` along rows.
#[derive(Clone, Debug)]
pub struct Piecewise2D {
    nu: usize,
    nv: usize,
    /// Picks a row in proportion to its total weight.
    rows: DiscreteDistribution,
    /// Picks a column within a row; `None` for rows of zero weight, which `rows` never picks.
    columns: Vec<Option<DiscreteDistribution>>,
}

impl Piecewise2D {
    /// `None` if the weights are not `nu·nv` finite non-negative numbers with a positive sum.
    pub fn new(weights: &[f32], nu: usize, nv: usize) -> Option<Piecewise2D> {
        if nu == 0 || nv == 0 || weights.len() != nu * nv {
            return None;
        }
        let columns: Vec<_> = weights
            .chunks_exact(nu)
            .map(DiscreteDistribution::new)
            .collect();
        let row_sums: Vec<f32> = weights
            .chunks_exact(nu)
            .map(|row| row.iter().map(|&w| w as f64).sum::<f64>() as f32)
            .collect();
        // A row of finite weights can still sum past f32's range.
        if row_sums.iter().any(|s| !s.is_finite()) {
            return None;
        }
        let rows = DiscreteDistribution::new(&row_sums)?;
        Some(Piecewise2D {
            nu,
            nv,
            rows,
            columns,
        })
    }

    /// Columns and rows.
    pub fn size(&self) -> (usize, usize) {
        (self.nu, self.nv)
    }

    /// The marginal distribution over rows, for the GPU's copy.
    pub(crate) fn rows(&self) -> &DiscreteDistribution {
        &self.rows
    }

    /// The conditional distribution over columns of each row (`None` for rows of zero weight),
    /// for the GPU's copy.
    pub(crate) fn columns(&self) -> &[Option<DiscreteDistribution>] {
        &self.columns
    }

    /// A point of `[0,1)²` for `u ∈ [0,1)²`, with its cell `(column, row)` and its density with
    /// respect to area on the square.
    pub fn sample(&self, u: Vec2) -> (Vec2, [usize; 2], f32) {
        let (row, p_row, fy) = self.rows.sample(u.y);
        let columns = self.columns[row]
            .as_ref()
            .expect("a row of positive weight has a column distribution");
        let (column, p_column, fx) = columns.sample(u.x);
        let p = Vec2::new(
            (column as f32 + fx) / self.nu as f32,
            (row as f32 + fy) / self.nv as f32,
        );
        let pdf = p_row * p_column * (self.nu * self.nv) as f32;
        (
            p.min(Vec2::splat(super::ONE_MINUS_EPSILON)),
            [column, row],
            pdf,
        )
    }

    /// Density of [`Piecewise2D::sample`] in the cell `(column, row)`.
    pub fn pdf_cell(&self, [column, row]: [usize; 2]) -> f32 {
        match self.columns.get(row) {
            Some(Some(columns)) => {
                self.rows.pmf(row) * columns.pmf(column) * (self.nu * self.nv) as f32
            }
            _ => 0.0,
        }
    }

    /// The cell holding `p ∈ [0,1]²` (the last cell owns the upper edges).
    pub fn cell(&self, p: Vec2) -> [usize; 2] {
        let index = |x: f32, n: usize| ((x * n as f32) as usize).min(n - 1);
        [index(p.x, self.nu), index(p.y, self.nv)]
    }

    /// Inverse of [`Piecewise2D::sample`]: the `u` that maps to `p`, for `p` in a cell of positive
    /// density.
    pub fn invert(&self, p: Vec2) -> Option<Vec2> {
        let [column, row] = self.cell(p);
        let columns = self.columns[row].as_ref()?;
        let fx = p.x * self.nu as f32 - column as f32;
        let fy = p.y * self.nv as f32 - row as f32;
        Some(Vec2::new(
            columns.invert(column, fx.clamp(0.0, 1.0)),
            self.rows.invert(row, fy.clamp(0.0, 1.0)),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    fn weights() -> (Vec<f32>, usize, usize) {
        // 4 × 3 with a zero cell, a zero row and a dominant cell.
        (
            vec![1.0, 0.0, 2.0, 3.0, 0.0, 0.0, 0.0, 0.0, 0.5, 40.0, 1.0, 0.25],
            4,
            3,
        )
    }

    #[test]
    fn rejects_invalid_weights() {
        assert!(Piecewise2D::new(&[1.0; 6], 4, 2).is_none());
        assert!(Piecewise2D::new(&[0.0; 6], 3, 2).is_none());
        assert!(Piecewise2D::new(&[1.0, f32::NAN], 2, 1).is_none());
        assert!(Piecewise2D::new(&[f32::MAX, f32::MAX], 2, 1).is_none());
        assert!(Piecewise2D::new(&[], 0, 0).is_none());
    }

    /// The density in each cell is its weight over the total, per unit area, and the sampled
    /// points land in each cell with that frequency (binomial z < 5 for 2e5 samples, seed 7).
    #[test]
    fn cell_density_and_frequency_match_the_weights() {
        let (w, nu, nv) = weights();
        let d = Piecewise2D::new(&w, nu, nv).unwrap();
        let total: f32 = w.iter().sum();
        for (k, &wk) in w.iter().enumerate() {
            let expected = wk / total * (nu * nv) as f32;
            let got = d.pdf_cell([k % nu, k / nu]);
            assert!(
                (got - expected).abs() <= 1e-6 * expected.max(1.0),
                "{k}: {got} {expected}"
            );
        }
        let n = 200_000;
        let mut counts = vec![0u32; w.len()];
        let mut rng = Rng::new(7, 0, 0);
        for _ in 0..n {
            let (p, cell, pdf) = d.sample(rng.next_2d());
            assert_eq!(d.cell(p), cell);
            assert_eq!(pdf, d.pdf_cell(cell));
            counts[cell[1] * nu + cell[0]] += 1;
        }
        for (k, &c) in counts.iter().enumerate() {
            let p = (w[k] / total) as f64;
            let z = (c as f64 - n as f64 * p) / (n as f64 * p * (1.0 - p)).sqrt().max(1e-9);
            assert!(
                z.abs() < 5.0 || (p == 0.0 && c == 0),
                "cell {k}: {c} of {n}, p {p}"
            );
        }
    }

    /// `invert` undoes `sample` (to f32 rounding of the CDFs), within cells and at their edges.
    #[test]
    fn invert_undoes_sample() {
        let (w, nu, nv) = weights();
        let d = Piecewise2D::new(&w, nu, nv).unwrap();
        let mut rng = Rng::new(8, 0, 0);
        for _ in 0..10_000 {
            let u = rng.next_2d();
            let (p, _, _) = d.sample(u);
            let back = d.invert(p).unwrap();
            assert!(
                (back - u).abs().max_element() < 2e-5,
                "{u} -> {p} -> {back}"
            );
        }
        assert!(
            d.invert(Vec2::new(0.3, 0.5)).is_none(),
            "the zero row has no inverse"
        );
    }
}
