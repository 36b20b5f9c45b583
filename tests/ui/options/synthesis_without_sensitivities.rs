// Synthesis needs the generated sensitivities: a mechanism declared without them is refused at
// compile time, naming the attribute to add.
kinloop::mechanism! {
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point p = a @ phi + b @ beta;
    }
}

use kinloop::synthesis::{Design, Problem, Task};

fn main() {
    let design = Design::new().var("b", 2.0, 4.0);
    let task = Task::path("p", [[1.0, 2.0], [1.5, 2.5], [2.0, 2.6]]).timed([0.0, 0.5, 1.0]);
    let _ = Problem::new(FourBar::default(), &design, &task);
}
