"""Design: geometry, materials and the optimization that chooses the wheel."""
