//! The default drawing's description, checked against each fixture mechanism's loops.

use kinloop::Mechanism;
use kinloop::drawing::Description;
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::roller_edger::RollerEdger;
use kinloop_fixtures::*;

fn text<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(_: &M) -> String {
    format!("== {}\n{}", M::NAME, Description::of::<M, N, NI, NO>().expect("reads"))
}

#[test]
fn print_all() {
    let all = [
        text(&RhombicDrive::default()),
        text(&DisplacerRodDrive::default()),
        text(&WorkingRodDrive::default()),
        text(&GearLever::default()),
        text(&RollerEdger::default()),
        text(&ClassFour::default()),
        text(&FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 }),
        text(&SliderCrank { r: 1.0, l: 3.0, e: 0.2 }),
        text(&FiveBar::default()),
    ];
    println!("{}", all.join("\n"));
}
