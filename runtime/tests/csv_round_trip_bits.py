"""The IEEE-754 bits of the edge values in `csv_round_trip.rs` and `serde_round_trip.rs`
(`edge_values_and_awkward_names_read_back_to_the_bit`, `a_table_of_edge_values_and_awkward_names_reads_back_from_json`,
`EDGES` of `serde_round_trip.rs` for its states, vectors and table of types, and of `fixtures/tests/serde_generated.rs`),
computed apart from kinloop and Rust: Python's own doubles, packed big-endian.

Printed (python3 runtime/tests/csv_round_trip_bits.py):
nan 7ff8000000000000
inf 7ff0000000000000
-inf fff0000000000000
0.0 0000000000000000
-0.0 8000000000000000
5e-324 0000000000000001
-2.225073858507201e-308 800fffffffffffff
2.2250738585072014e-308 0010000000000000
1e+308 7fe1ccf385ebc8a0
-1.7976931348623157e+308 ffefffffffffffff
0.30000000000000004 3fd3333333333334
"""
import struct

VALUES = [
    float("nan"),
    float("inf"),
    -float("inf"),
    0.0,
    -0.0,
    5e-324,  # the smallest subnormal
    -2.225073858507201e-308,  # the largest subnormal, negated
    2.2250738585072014e-308,  # the smallest normal, f64::MIN_POSITIVE
    1e308,
    -1.7976931348623157e308,  # -f64::MAX
    0.1 + 0.2,
]

for v in VALUES:
    print(repr(v), struct.pack(">d", v).hex())
