//! The README shows what the binary does: every command of its `console` blocks runs, exits as
//! shown, and prints what is shown (`...` stands for lines left out).

#[test]
fn the_readmes_commands_print_what_it_shows() {
    trycmd::TestCases::new()
        .register_bin("hw3", std::path::Path::new(env!("CARGO_BIN_EXE_hw3")))
        .case(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"));
}
