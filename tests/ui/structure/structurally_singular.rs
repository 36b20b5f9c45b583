kinloop::mechanism! {
    /// Rhombic drive with a wrong angle in the second contour: counts match, structure does not.
    pub struct RhombicDrive {
        params r_p, r_b, l_p, l_b, e_p, de, gamma;
        input phi1;
        unknowns phi2, phi4, x_c, x_f;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        // Typo: the displacer rod's angle is `phi4`, not `phi2`.
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi2;
    }
}

fn main() {}
