fn main() {
    for t in std::env::args().skip(1) {
        let p = rotlang::parse(&t, rotlang::Target::Sparse);
        println!("{t:?}: {} instr", p.template.instructions.len());
        for d in &p.diagnostics {
            println!(
                "  {:?} {} {} {:?} help={:?}",
                d.severity,
                d.code,
                d.message,
                d.labels
                    .iter()
                    .map(|l| (&t[l.span.range()], &l.message))
                    .collect::<Vec<_>>(),
                d.help
            );
        }
    }
}
