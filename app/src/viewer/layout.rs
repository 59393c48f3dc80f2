//! Where the panes go: the grid (columns × rows) that shows `n` images of one size largest in the
//! image area, each cell with a caption line above it. Three 16:9 panes in a wide window, say,
//! go two by two rather than in one row of small images.

/// Height of a pane's caption line (points).
pub const CAPTION: f32 = 18.0;
/// Gap between cells (points).
pub const GAP: f32 = 6.0;

/// The panes' arrangement in an area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// Columns.
    pub cols: usize,
    /// Rows.
    pub rows: usize,
    /// Size of each cell's image area (below its caption).
    pub cell: egui::Vec2,
}

impl Grid {
    /// The largest scale (points per pixel) at which an `image` fits a cell.
    pub fn fit(&self, image: egui::Vec2) -> f32 {
        super::zoom::fit_scale(self.cell, image)
    }
}

/// The grid for `n` panes of `image` pixels in `area` whose cells fit the image largest; among
/// equally good grids (within 1 %), the one with fewer rows.
pub fn best_grid(n: usize, area: egui::Vec2, image: egui::Vec2) -> Grid {
    let n = n.max(1);
    let mut best: Option<(f32, Grid)> = None;
    for cols in 1..=n {
        let rows = n.div_ceil(cols);
        let cell = egui::vec2(
            (area.x - GAP * (cols - 1) as f32) / cols as f32,
            (area.y - GAP * (rows - 1) as f32) / rows as f32 - CAPTION,
        )
        .max(egui::vec2(1.0, 1.0));
        let grid = Grid { cols, rows, cell };
        let fit = grid.fit(image);
        // Iterating from fewest columns (most rows), a later grid wins on a tie (fewer rows).
        if best.is_none_or(|(b, _)| fit >= b * 0.99) {
            best = Some((fit, grid));
        }
    }
    best.expect("n ≥ 1").1
}

/// The caption line and the image cell of pane `i` of `grid` in `area` (row-major).
pub fn cell_rects(area: egui::Rect, grid: &Grid, i: usize) -> (egui::Rect, egui::Rect) {
    let (col, row) = (i % grid.cols, i / grid.cols);
    let min = area.min
        + egui::vec2(
            col as f32 * (grid.cell.x + GAP),
            row as f32 * (grid.cell.y + CAPTION + GAP),
        );
    let caption = egui::Rect::from_min_size(min, egui::vec2(grid.cell.x, CAPTION));
    let cell = egui::Rect::from_min_size(min + egui::vec2(0.0, CAPTION), grid.cell);
    (caption, cell)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The case: Veach's scene (320×180) in three panes of a 1400×900 window. One row
    /// draws them 285 points wide; the grid draws them larger than the image.
    #[test]
    fn three_wide_panes_go_two_by_two_when_that_is_larger() {
        let image = egui::vec2(320.0, 180.0);
        let area = egui::vec2(860.0, 620.0);
        let g = best_grid(3, area, image);
        assert_eq!((g.cols, g.rows), (2, 2));
        assert!(g.fit(image) > 1.3, "{g:?}");
        let one_row = (area.x - 2.0 * GAP) / 3.0 / image.x;
        assert!(g.fit(image) > 1.4 * one_row);
    }

    #[test]
    fn square_images_in_a_wide_area_stay_in_one_row() {
        let g = best_grid(3, egui::vec2(1500.0, 500.0), egui::vec2(256.0, 256.0));
        assert_eq!((g.cols, g.rows), (3, 1));
        let g = best_grid(1, egui::vec2(800.0, 600.0), egui::vec2(256.0, 256.0));
        assert_eq!(
            (g.cols, g.rows, g.cell),
            (1, 1, egui::vec2(800.0, 600.0 - CAPTION))
        );
    }

    #[test]
    fn cells_tile_the_area_without_overlap() {
        let area = egui::Rect::from_min_size(egui::pos2(5.0, 7.0), egui::vec2(860.0, 620.0));
        let g = best_grid(3, area.size(), egui::vec2(320.0, 180.0));
        let cells: Vec<_> = (0..3).map(|i| cell_rects(area, &g, i)).collect();
        for (i, (cap, cell)) in cells.iter().enumerate() {
            assert!(area.contains_rect(*cell) && area.contains_rect(*cap), "{i}");
            assert_eq!(cap.max.y, cell.min.y);
            for (cap2, cell2) in &cells[i + 1..] {
                assert!(!cell.intersects(cell2.shrink(0.5)) && !cap.intersects(cap2.shrink(0.5)));
            }
        }
    }
}
