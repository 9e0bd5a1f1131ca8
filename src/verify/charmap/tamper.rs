//! The deliberate weakening of the cell certificate that the soundness tests use.

/// How the cell certificate may be weakened on purpose, to show that the
/// soundness tests catch an unsound enclosure. Never set by the CLI.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CellTamper {
    /// The sound certificate.
    #[default]
    None,
    /// Drop the variation of the invariant subspace over the cell: NURDS
    /// takes `rho = 0` (the centre's basis for every `r`), the `c` path
    /// evaluates the eigenvector at the cell's midpoint only.
    DropSubspaceVariation,
    /// Shrink Stewart's radius: NURDS takes `rho / 64` for the ball of `P`
    /// and drops the bound of its second-order part.
    ShrinkStewartRadius,
    /// Drop the cross term `a_01 a_10` from the discriminant of the 2 x 2
    /// eigenvalue bounds of the pair and of the rest (NURDS, `g1`).
    DropPairCrossTerm,
    /// Divide the bound `b` of the subspace operator's variation
    /// `||L0^{-1} dL_r||` by 8 (NURDS).
    ShrinkSubspaceVariation,
}
