//! The `bspcsg` command line tool.

fn main() {
    eprintln!("bspcsg: the command line arrives with mesh file support");
    std::process::exit(1);
}
