//! A regular 2D grid of samples with bilinear interpolation (Zhang Sec. 5.5.1, Eq. 11-13).

/// `width x height` samples, row-major (`z` rows of `x` samples).
#[derive(Clone, Debug, PartialEq)]
pub struct Grid<T> {
    width: usize,
    height: usize,
    data: Vec<T>,
}

impl<T: Copy> Grid<T> {
    /// A grid filled with `value`.
    pub fn filled(width: usize, height: usize, value: T) -> Self {
        Self {
            width,
            height,
            data: vec![value; width * height],
        }
    }

    /// A grid from row-major data; `None` when the length is not `width * height`.
    pub fn from_vec(width: usize, height: usize, data: Vec<T>) -> Option<Self> {
        (data.len() == width * height && width > 0 && height > 0).then_some(Self {
            width,
            height,
            data,
        })
    }

    /// A grid whose sample `(i, j)` is `f(i, j)`.
    pub fn from_fn(width: usize, height: usize, mut f: impl FnMut(usize, usize) -> T) -> Self {
        let mut data = Vec::with_capacity(width * height);
        for j in 0..height {
            for i in 0..width {
                data.push(f(i, j));
            }
        }
        Self {
            width,
            height,
            data,
        }
    }

    /// Samples along x.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Samples along z.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Row-major samples.
    pub fn data(&self) -> &[T] {
        &self.data
    }

    /// Sample `(i, j)`, clamped to the grid.
    pub fn get(&self, i: isize, j: isize) -> T {
        let i = i.clamp(0, self.width as isize - 1) as usize;
        let j = j.clamp(0, self.height as isize - 1) as usize;
        self.data[j * self.width + i]
    }

    /// The sample nearest to normalised coordinates `(u, v)` in `[0, 1]`.
    pub fn nearest(&self, u: f32, v: f32) -> T {
        let i = (u * (self.width - 1) as f32).round() as isize;
        let j = (v * (self.height - 1) as f32).round() as isize;
        self.get(i, j)
    }
}

impl Grid<f32> {
    /// Bilinear interpolation at normalised `(u, v)` in `[0, 1]` (clamped), where `(0, 0)` is
    /// the first sample and `(1, 1)` the last. Zhang Eq. 11-12 interpolate along x between the
    /// four surrounding samples P11, P21 (giving Q1) and P12, P22 (giving Q2); Eq. 13
    /// interpolates Q1 and Q2 along z.
    pub fn bilinear(&self, u: f32, v: f32) -> f32 {
        let x = u.clamp(0.0, 1.0) * (self.width - 1) as f32;
        let z = v.clamp(0.0, 1.0) * (self.height - 1) as f32;
        let (x1, z1) = (x.floor(), z.floor());
        let (fx, fz) = (x - x1, z - z1);
        let (i, j) = (x1 as isize, z1 as isize);
        let q1 = self.get(i, j) * (1.0 - fx) + self.get(i + 1, j) * fx; // Eq. 11
        let q2 = self.get(i, j + 1) * (1.0 - fx) + self.get(i + 1, j + 1) * fx; // Eq. 12
        q1 * (1.0 - fz) + q2 * fz // Eq. 13
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_hits_samples_and_interpolates_between() {
        let g = Grid::from_vec(2, 2, vec![0.0, 1.0, 2.0, 3.0]).unwrap();
        assert_eq!(g.bilinear(0.0, 0.0), 0.0);
        assert_eq!(g.bilinear(1.0, 0.0), 1.0);
        assert_eq!(g.bilinear(0.0, 1.0), 2.0);
        assert_eq!(g.bilinear(1.0, 1.0), 3.0);
        assert!((g.bilinear(0.5, 0.5) - 1.5).abs() < 1e-6);
        assert!((g.bilinear(0.25, 0.0) - 0.25).abs() < 1e-6);
        // Clamped outside.
        assert_eq!(g.bilinear(-3.0, 7.0), 2.0);
    }

    #[test]
    fn from_vec_rejects_wrong_length() {
        assert!(Grid::from_vec(3, 3, vec![0u8; 8]).is_none());
        assert!(Grid::from_vec(0, 3, Vec::<u8>::new()).is_none());
    }
}
