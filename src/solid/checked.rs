//! A solid's mesh held to its own report: what the command line promises (a result that is not
//! a closed 2-manifold is never passed on as if it were), for library callers.

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::solid::Solid;

impl Solid {
    /// [`Solid::to_mesh`], checked: the mesh of a solid within the precision contract that is
    /// a closed 2-manifold (or empty). What the command line writes, and what a caller passing
    /// the result on (to a file, a slicer, another program) can rely on.
    ///
    /// The booleans of solids are meant to give solids; where they do not (a fault of the
    /// kernel on hard input: a feature 10⁻²⁰ of its neighbour's size, a difference of nearly
    /// equal operands), this says so instead of handing over a broken mesh; a caller that
    /// wants the mesh anyway takes [`Solid::to_mesh`].
    ///
    /// ```
    /// use bspcsg::{Error, Solid};
    /// use bspcsg::glam::DVec3;
    /// let a = Solid::cube(1.0)?;
    /// let b = Solid::cube(1.0)?.translate(DVec3::splat(0.5))?;
    /// let mesh = (&a | &b).to_checked_mesh()?;
    /// assert!(mesh.report().is_closed_manifold());
    /// // Taking the mesh even when it is broken:
    /// let mesh = match (&a - &b).to_checked_mesh() {
    ///     Ok(mesh) => mesh,
    ///     Err(Error::BrokenResult { .. }) => (&a - &b).to_mesh(),
    ///     Err(e) => return Err(e),
    /// };
    /// assert!((mesh.volume() - 0.875).abs() < 1e-12);
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::BeyondBudget`] as [`Solid::check_budget`], [`Error::BeyondPrecision`] as
    /// [`Solid::check_precision`], and [`Error::BrokenResult`]
    /// with the mesh's [`MeshReport`](crate::MeshReport) as text when the mesh is not empty
    /// and not a closed 2-manifold.
    pub fn to_checked_mesh(&self) -> Result<Mesh> {
        self.check_budget()?;
        self.check_precision()?;
        let mesh = self.to_mesh();
        let report = mesh.report();
        if mesh.is_empty() || report.is_closed_manifold() {
            return Ok(mesh);
        }
        Err(Error::BrokenResult {
            report: report.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::error::Error;
    use crate::mesh::Mesh;
    use crate::solid::Solid;

    #[test]
    fn a_broken_solid_is_refused_with_its_report_and_mesh() {
        // One face of a cube: open, as no boolean of solids should leave it.
        let cube = Solid::cube(1.0).unwrap();
        let open: Vec<_> = cube.polygons().iter().take(1).cloned().collect();
        let open = Solid::from_polygons(open);
        match open.to_checked_mesh() {
            Err(e @ Error::BrokenResult { .. }) => {
                let Error::BrokenResult { report } = &e else {
                    unreachable!()
                };
                assert_eq!(*report, open.to_mesh().report().to_string());
                assert!(report.contains("NOT a closed 2-manifold"), "{report}");
                assert!(e.to_string().contains("not a closed 2-manifold"), "{e}");
            }
            other => panic!("{other:?}"),
        }
        assert!(
            cube.to_checked_mesh()
                .unwrap()
                .report()
                .is_closed_manifold()
        );
        assert_eq!(Solid::default().to_checked_mesh().unwrap(), Mesh::default());
        // Beyond precision: two unit cubes overlapping by half 10¹² from the origin.
        let far = |x: f64| {
            Solid::cube(1.0)
                .unwrap()
                .translate(DVec3::new(x, 1e12, 0.0))
                .unwrap()
        };
        let both = &far(0.0) | &far(0.5);
        assert!(matches!(
            both.to_checked_mesh(),
            Err(Error::BeyondPrecision { .. })
        ));
    }
}
