// A declaration copied with the macro around it; read at run time (a `.kl` file), the same text
// is the one a file would hold.
kinloop::mechanism! {
    kinloop::mechanism! {
        pub struct Cam {
            params h = 0.02;
            input phi;
            unknowns s;
            eq lift: s == h * sin(phi);
        }
    }
}

fn main() {}
