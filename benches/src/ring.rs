//! A ring of 64 four-bar loops closed through a differential, and the same 64 loops in series
//! (the large coupled block). Loop `i` is the four-bar `a @ driver + b @ u_i == (d, 0) +
//! c @ v_i`, driven by the rocker `v_(i-1)` of the loop before; in the series the first loop is
//! driven by the input `phi`, in the ring by the carrier of a differential whose side gears are
//! the input and the last rocker, `(phi + v_63) / 2`. The series is 64 blocks of two (each
//! a closed-form RRR dyad); the ring is one block of 128 unknowns with 3 non-zeros per Jacobian
//! row. Written out (a declaration is tokens, not a loop); [`crate::expansion::four_bar_ring`]
//! and [`crate::expansion::four_bar_chain`] generate the same bodies for any number of loops
//! (`benches/tests/sparse_ring.rs` checks that they agree).

use kinloop_fixtures::declare;

declare! {
    /// The ring's declaration text.
    RING => {
        /// 64 four-bar loops closed through a differential: one sparse Newton block.
        pub struct Ring, dense RingDense {
            params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
            input phi;
            unknowns
                u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
                u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9,
                u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9,
                u12 = 0.6, v12 = 1.9, u13 = 0.6, v13 = 1.9, u14 = 0.6, v14 = 1.9, u15 = 0.6, v15 = 1.9,
                u16 = 0.6, v16 = 1.9, u17 = 0.6, v17 = 1.9, u18 = 0.6, v18 = 1.9, u19 = 0.6, v19 = 1.9,
                u20 = 0.6, v20 = 1.9, u21 = 0.6, v21 = 1.9, u22 = 0.6, v22 = 1.9, u23 = 0.6, v23 = 1.9,
                u24 = 0.6, v24 = 1.9, u25 = 0.6, v25 = 1.9, u26 = 0.6, v26 = 1.9, u27 = 0.6, v27 = 1.9,
                u28 = 0.6, v28 = 1.9, u29 = 0.6, v29 = 1.9, u30 = 0.6, v30 = 1.9, u31 = 0.6, v31 = 1.9,
                u32 = 0.6, v32 = 1.9, u33 = 0.6, v33 = 1.9, u34 = 0.6, v34 = 1.9, u35 = 0.6, v35 = 1.9,
                u36 = 0.6, v36 = 1.9, u37 = 0.6, v37 = 1.9, u38 = 0.6, v38 = 1.9, u39 = 0.6, v39 = 1.9,
                u40 = 0.6, v40 = 1.9, u41 = 0.6, v41 = 1.9, u42 = 0.6, v42 = 1.9, u43 = 0.6, v43 = 1.9,
                u44 = 0.6, v44 = 1.9, u45 = 0.6, v45 = 1.9, u46 = 0.6, v46 = 1.9, u47 = 0.6, v47 = 1.9,
                u48 = 0.6, v48 = 1.9, u49 = 0.6, v49 = 1.9, u50 = 0.6, v50 = 1.9, u51 = 0.6, v51 = 1.9,
                u52 = 0.6, v52 = 1.9, u53 = 0.6, v53 = 1.9, u54 = 0.6, v54 = 1.9, u55 = 0.6, v55 = 1.9,
                u56 = 0.6, v56 = 1.9, u57 = 0.6, v57 = 1.9, u58 = 0.6, v58 = 1.9, u59 = 0.6, v59 = 1.9,
                u60 = 0.6, v60 = 1.9, u61 = 0.6, v61 = 1.9, u62 = 0.6, v62 = 1.9, u63 = 0.6, v63 = 1.9;
            loop l0: a @ (0.5 * (phi + v63)) + b @ u0 == (d, 0) + c @ v0;
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
            loop l16: a @ v15 + b @ u16 == (d, 0) + c @ v16;
            loop l17: a @ v16 + b @ u17 == (d, 0) + c @ v17;
            loop l18: a @ v17 + b @ u18 == (d, 0) + c @ v18;
            loop l19: a @ v18 + b @ u19 == (d, 0) + c @ v19;
            loop l20: a @ v19 + b @ u20 == (d, 0) + c @ v20;
            loop l21: a @ v20 + b @ u21 == (d, 0) + c @ v21;
            loop l22: a @ v21 + b @ u22 == (d, 0) + c @ v22;
            loop l23: a @ v22 + b @ u23 == (d, 0) + c @ v23;
            loop l24: a @ v23 + b @ u24 == (d, 0) + c @ v24;
            loop l25: a @ v24 + b @ u25 == (d, 0) + c @ v25;
            loop l26: a @ v25 + b @ u26 == (d, 0) + c @ v26;
            loop l27: a @ v26 + b @ u27 == (d, 0) + c @ v27;
            loop l28: a @ v27 + b @ u28 == (d, 0) + c @ v28;
            loop l29: a @ v28 + b @ u29 == (d, 0) + c @ v29;
            loop l30: a @ v29 + b @ u30 == (d, 0) + c @ v30;
            loop l31: a @ v30 + b @ u31 == (d, 0) + c @ v31;
            loop l32: a @ v31 + b @ u32 == (d, 0) + c @ v32;
            loop l33: a @ v32 + b @ u33 == (d, 0) + c @ v33;
            loop l34: a @ v33 + b @ u34 == (d, 0) + c @ v34;
            loop l35: a @ v34 + b @ u35 == (d, 0) + c @ v35;
            loop l36: a @ v35 + b @ u36 == (d, 0) + c @ v36;
            loop l37: a @ v36 + b @ u37 == (d, 0) + c @ v37;
            loop l38: a @ v37 + b @ u38 == (d, 0) + c @ v38;
            loop l39: a @ v38 + b @ u39 == (d, 0) + c @ v39;
            loop l40: a @ v39 + b @ u40 == (d, 0) + c @ v40;
            loop l41: a @ v40 + b @ u41 == (d, 0) + c @ v41;
            loop l42: a @ v41 + b @ u42 == (d, 0) + c @ v42;
            loop l43: a @ v42 + b @ u43 == (d, 0) + c @ v43;
            loop l44: a @ v43 + b @ u44 == (d, 0) + c @ v44;
            loop l45: a @ v44 + b @ u45 == (d, 0) + c @ v45;
            loop l46: a @ v45 + b @ u46 == (d, 0) + c @ v46;
            loop l47: a @ v46 + b @ u47 == (d, 0) + c @ v47;
            loop l48: a @ v47 + b @ u48 == (d, 0) + c @ v48;
            loop l49: a @ v48 + b @ u49 == (d, 0) + c @ v49;
            loop l50: a @ v49 + b @ u50 == (d, 0) + c @ v50;
            loop l51: a @ v50 + b @ u51 == (d, 0) + c @ v51;
            loop l52: a @ v51 + b @ u52 == (d, 0) + c @ v52;
            loop l53: a @ v52 + b @ u53 == (d, 0) + c @ v53;
            loop l54: a @ v53 + b @ u54 == (d, 0) + c @ v54;
            loop l55: a @ v54 + b @ u55 == (d, 0) + c @ v55;
            loop l56: a @ v55 + b @ u56 == (d, 0) + c @ v56;
            loop l57: a @ v56 + b @ u57 == (d, 0) + c @ v57;
            loop l58: a @ v57 + b @ u58 == (d, 0) + c @ v58;
            loop l59: a @ v58 + b @ u59 == (d, 0) + c @ v59;
            loop l60: a @ v59 + b @ u60 == (d, 0) + c @ v60;
            loop l61: a @ v60 + b @ u61 == (d, 0) + c @ v61;
            loop l62: a @ v61 + b @ u62 == (d, 0) + c @ v62;
            loop l63: a @ v62 + b @ u63 == (d, 0) + c @ v63;
        }
    }
}

declare! {
    /// The series' declaration text.
    SERIES => {
        /// The same 64 four-bar loops in series: 64 closed-form blocks.
        pub struct Series {
            params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
            input phi;
            unknowns
                u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
                u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9,
                u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9,
                u12 = 0.6, v12 = 1.9, u13 = 0.6, v13 = 1.9, u14 = 0.6, v14 = 1.9, u15 = 0.6, v15 = 1.9,
                u16 = 0.6, v16 = 1.9, u17 = 0.6, v17 = 1.9, u18 = 0.6, v18 = 1.9, u19 = 0.6, v19 = 1.9,
                u20 = 0.6, v20 = 1.9, u21 = 0.6, v21 = 1.9, u22 = 0.6, v22 = 1.9, u23 = 0.6, v23 = 1.9,
                u24 = 0.6, v24 = 1.9, u25 = 0.6, v25 = 1.9, u26 = 0.6, v26 = 1.9, u27 = 0.6, v27 = 1.9,
                u28 = 0.6, v28 = 1.9, u29 = 0.6, v29 = 1.9, u30 = 0.6, v30 = 1.9, u31 = 0.6, v31 = 1.9,
                u32 = 0.6, v32 = 1.9, u33 = 0.6, v33 = 1.9, u34 = 0.6, v34 = 1.9, u35 = 0.6, v35 = 1.9,
                u36 = 0.6, v36 = 1.9, u37 = 0.6, v37 = 1.9, u38 = 0.6, v38 = 1.9, u39 = 0.6, v39 = 1.9,
                u40 = 0.6, v40 = 1.9, u41 = 0.6, v41 = 1.9, u42 = 0.6, v42 = 1.9, u43 = 0.6, v43 = 1.9,
                u44 = 0.6, v44 = 1.9, u45 = 0.6, v45 = 1.9, u46 = 0.6, v46 = 1.9, u47 = 0.6, v47 = 1.9,
                u48 = 0.6, v48 = 1.9, u49 = 0.6, v49 = 1.9, u50 = 0.6, v50 = 1.9, u51 = 0.6, v51 = 1.9,
                u52 = 0.6, v52 = 1.9, u53 = 0.6, v53 = 1.9, u54 = 0.6, v54 = 1.9, u55 = 0.6, v55 = 1.9,
                u56 = 0.6, v56 = 1.9, u57 = 0.6, v57 = 1.9, u58 = 0.6, v58 = 1.9, u59 = 0.6, v59 = 1.9,
                u60 = 0.6, v60 = 1.9, u61 = 0.6, v61 = 1.9, u62 = 0.6, v62 = 1.9, u63 = 0.6, v63 = 1.9;
            loop l0: a @ phi + b @ u0 == (d, 0) + c @ v0;
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
            loop l16: a @ v15 + b @ u16 == (d, 0) + c @ v16;
            loop l17: a @ v16 + b @ u17 == (d, 0) + c @ v17;
            loop l18: a @ v17 + b @ u18 == (d, 0) + c @ v18;
            loop l19: a @ v18 + b @ u19 == (d, 0) + c @ v19;
            loop l20: a @ v19 + b @ u20 == (d, 0) + c @ v20;
            loop l21: a @ v20 + b @ u21 == (d, 0) + c @ v21;
            loop l22: a @ v21 + b @ u22 == (d, 0) + c @ v22;
            loop l23: a @ v22 + b @ u23 == (d, 0) + c @ v23;
            loop l24: a @ v23 + b @ u24 == (d, 0) + c @ v24;
            loop l25: a @ v24 + b @ u25 == (d, 0) + c @ v25;
            loop l26: a @ v25 + b @ u26 == (d, 0) + c @ v26;
            loop l27: a @ v26 + b @ u27 == (d, 0) + c @ v27;
            loop l28: a @ v27 + b @ u28 == (d, 0) + c @ v28;
            loop l29: a @ v28 + b @ u29 == (d, 0) + c @ v29;
            loop l30: a @ v29 + b @ u30 == (d, 0) + c @ v30;
            loop l31: a @ v30 + b @ u31 == (d, 0) + c @ v31;
            loop l32: a @ v31 + b @ u32 == (d, 0) + c @ v32;
            loop l33: a @ v32 + b @ u33 == (d, 0) + c @ v33;
            loop l34: a @ v33 + b @ u34 == (d, 0) + c @ v34;
            loop l35: a @ v34 + b @ u35 == (d, 0) + c @ v35;
            loop l36: a @ v35 + b @ u36 == (d, 0) + c @ v36;
            loop l37: a @ v36 + b @ u37 == (d, 0) + c @ v37;
            loop l38: a @ v37 + b @ u38 == (d, 0) + c @ v38;
            loop l39: a @ v38 + b @ u39 == (d, 0) + c @ v39;
            loop l40: a @ v39 + b @ u40 == (d, 0) + c @ v40;
            loop l41: a @ v40 + b @ u41 == (d, 0) + c @ v41;
            loop l42: a @ v41 + b @ u42 == (d, 0) + c @ v42;
            loop l43: a @ v42 + b @ u43 == (d, 0) + c @ v43;
            loop l44: a @ v43 + b @ u44 == (d, 0) + c @ v44;
            loop l45: a @ v44 + b @ u45 == (d, 0) + c @ v45;
            loop l46: a @ v45 + b @ u46 == (d, 0) + c @ v46;
            loop l47: a @ v46 + b @ u47 == (d, 0) + c @ v47;
            loop l48: a @ v47 + b @ u48 == (d, 0) + c @ v48;
            loop l49: a @ v48 + b @ u49 == (d, 0) + c @ v49;
            loop l50: a @ v49 + b @ u50 == (d, 0) + c @ v50;
            loop l51: a @ v50 + b @ u51 == (d, 0) + c @ v51;
            loop l52: a @ v51 + b @ u52 == (d, 0) + c @ v52;
            loop l53: a @ v52 + b @ u53 == (d, 0) + c @ v53;
            loop l54: a @ v53 + b @ u54 == (d, 0) + c @ v54;
            loop l55: a @ v54 + b @ u55 == (d, 0) + c @ v55;
            loop l56: a @ v55 + b @ u56 == (d, 0) + c @ v56;
            loop l57: a @ v56 + b @ u57 == (d, 0) + c @ v57;
            loop l58: a @ v57 + b @ u58 == (d, 0) + c @ v58;
            loop l59: a @ v58 + b @ u59 == (d, 0) + c @ v59;
            loop l60: a @ v59 + b @ u60 == (d, 0) + c @ v60;
            loop l61: a @ v60 + b @ u61 == (d, 0) + c @ v61;
            loop l62: a @ v61 + b @ u62 == (d, 0) + c @ v62;
            loop l63: a @ v62 + b @ u63 == (d, 0) + c @ v63;
        }
    }
}
