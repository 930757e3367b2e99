//! Weighted least-squares plane `z = a·x + b·y + c`.

/// Running sums for a weighted plane fit (f64: sums of a few thousand samples).
#[derive(Debug, Clone, Copy, Default)]
pub struct PlaneFit {
    sw: f64,
    sx: f64,
    sy: f64,
    sz: f64,
    sxx: f64,
    sxy: f64,
    syy: f64,
    sxz: f64,
    syz: f64,
}

/// A plane `z = a·x + b·y + c`, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// dz/dx.
    pub a: f64,
    /// dz/dy.
    pub b: f64,
    /// z at x = y = 0, metres.
    pub c: f64,
}

impl Plane {
    /// Height of the plane at (x, y).
    #[inline]
    pub fn z(&self, x: f64, y: f64) -> f64 {
        self.a * x + self.b * y + self.c
    }

    /// Where the plane meets the ground z = 0 at lateral position `y`: the toe
    /// line's x there, metres (infinite for a plane with no slope along x).
    #[inline]
    pub fn toe_x(&self, y: f64) -> f64 {
        -(self.b * y + self.c) / self.a
    }

    /// The steepest slope of the plane, degrees (always ≥ 0).
    pub fn gradient_deg(&self) -> f64 {
        self.a.hypot(self.b).atan().to_degrees()
    }
}

impl PlaneFit {
    /// Add a sample with weight `w`.
    #[inline]
    pub fn add(&mut self, x: f64, y: f64, z: f64, w: f64) {
        self.sw += w;
        self.sx += w * x;
        self.sy += w * y;
        self.sz += w * z;
        self.sxx += w * x * x;
        self.sxy += w * x * y;
        self.syy += w * y * y;
        self.sxz += w * x * z;
        self.syz += w * y * z;
    }

    /// Total weight added.
    pub fn weight(&self) -> f64 {
        self.sw
    }

    /// Solve the normal equations (centred, for conditioning). When the samples span
    /// no width in y (a single strip), fits `z = a·x + c` with `b = 0`. `None` when
    /// they span no length in x either.
    pub fn solve(&self) -> Option<Plane> {
        if self.sw <= 0.0 {
            return None;
        }
        let (mx, my, mz) = (self.sx / self.sw, self.sy / self.sw, self.sz / self.sw);
        // Centred second moments.
        let cxx = self.sxx / self.sw - mx * mx;
        let cxy = self.sxy / self.sw - mx * my;
        let cyy = self.syy / self.sw - my * my;
        let cxz = self.sxz / self.sw - mx * mz;
        let cyz = self.syz / self.sw - my * mz;
        let det = cxx * cyy - cxy * cxy;
        let (a, b) = if det > 1e-9 * (cxx * cyy).max(1e-18) && cyy > 1e-8 {
            ((cxz * cyy - cyz * cxy) / det, (cyz * cxx - cxz * cxy) / det)
        } else if cxx > 1e-8 {
            (cxz / cxx, 0.0)
        } else {
            return None;
        };
        Some(Plane {
            a,
            b,
            c: mz - a * mx - b * my,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_an_exact_plane() {
        let mut f = PlaneFit::default();
        for i in 0..10 {
            for j in 0..5 {
                let (x, y) = (1.0 + i as f64 * 0.05, 0.2 + j as f64 * 0.05);
                f.add(x, y, 0.3 * x - 0.1 * y + 0.05, 1.0 + i as f64);
            }
        }
        let p = f.solve().unwrap();
        assert!((p.a - 0.3).abs() < 1e-9 && (p.b + 0.1).abs() < 1e-9 && (p.c - 0.05).abs() < 1e-9);
        assert!((p.gradient_deg() - 0.1f64.hypot(0.3).atan().to_degrees()).abs() < 1e-9);
    }

    #[test]
    fn single_strip_fits_a_line_and_a_point_fits_nothing() {
        let mut f = PlaneFit::default();
        for i in 0..5 {
            let x = i as f64 * 0.1;
            f.add(x, 0.45, 2.0 * x, 1.0);
        }
        let p = f.solve().unwrap();
        assert!((p.a - 2.0).abs() < 1e-9 && p.b == 0.0);
        let mut g = PlaneFit::default();
        g.add(1.0, 1.0, 1.0, 1.0);
        assert!(g.solve().is_none());
        assert!(PlaneFit::default().solve().is_none());
    }
}
