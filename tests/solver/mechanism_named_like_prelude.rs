//! A mechanism may be named like a type of the prelude that is not a variant (`Option`,
//! `Result`, `Vec`): its struct shadows the prelude's in its module, so the code `mechanism!`
//! generates names those types by their paths, the sparse Newton block's too.

mod named_option {
    kinloop::mechanism! {
        /// 16 four-bar loops closed into a ring: one sparse block of 32.
        pub struct Option {
            params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
            input phi;
            unknowns
                u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
                u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9,
                u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9,
                u12 = 0.6, v12 = 1.9, u13 = 0.6, v13 = 1.9, u14 = 0.6, v14 = 1.9, u15 = 0.6, v15 = 1.9;
            loop l0: a @ (0.5 * (phi + v15)) + b @ u0 == (d, 0) + c @ v0;
            loop l1: a @ v0 + b @ u1 == (d, 0) + c @ v1;
            loop l2: a @ v1 + b @ u2 == (d, 0) + c @ v2;
            loop l3: a @ v2 + b @ u3 == (d, 0) + c @ v3;
            loop l4: a @ v3 + b @ u4 == (d, 0) + c @ v4;
            loop l5: a @ v4 + b @ u5 == (d, 0) + c @ v5;
            loop l6: a @ v5 + b @ u6 == (d, 0) + c @ v6;
            loop l7: a @ v6 + b @ u7 == (d, 0) + c @ v7;
            loop l8: a @ v7 + b @ u8 == (d, 0) + c @ v8;
            loop l9: a @ v8 + b @ u9 == (d, 0) + c @ v9;
            loop l10: a @ v9 + b @ u10 == (d, 0) + c @ v10;
            loop l11: a @ v10 + b @ u11 == (d, 0) + c @ v11;
            loop l12: a @ v11 + b @ u12 == (d, 0) + c @ v12;
            loop l13: a @ v12 + b @ u13 == (d, 0) + c @ v13;
            loop l14: a @ v13 + b @ u14 == (d, 0) + c @ v14;
            loop l15: a @ v14 + b @ u15 == (d, 0) + c @ v15;
        }
    }

    #[test]
    fn a_sparse_mechanism_named_option_solves() {
        assert!(Option::DECOMPOSITION.contains("sparse"), "{}", Option::DECOMPOSITION);
        let s = Option::default().solve(0.3).expect("the ring assembles");
        assert!(s.q.v15.is_finite() && s.dq.v15.is_finite());
    }
}
