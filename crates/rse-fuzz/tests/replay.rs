//! Every seed and every input a fuzz target ever failed on
//! (`fuzz/seeds/<target>/`, `fuzz/regressions/<target>/`), replayed
//! through the target's body on the stable toolchain.

use std::path::PathBuf;

#[test]
fn every_kept_input_passes_its_target() {
    let fuzz = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    for (target, body) in rse_fuzz::TARGETS {
        let mut replayed = 0;
        for kind in ["seeds", "regressions"] {
            let Ok(entries) = std::fs::read_dir(fuzz.join(kind).join(target)) else {
                continue;
            };
            for entry in entries {
                let path = entry.unwrap().path();
                let data = std::fs::read(&path).unwrap();
                eprintln!("{}", path.display());
                body(&data);
                replayed += 1;
            }
        }
        assert!(replayed > 0, "no seed kept for the {target} target");
    }
}

#[test]
fn the_manifest_seed_is_the_good_world() {
    let seed =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/seeds/manifest/good.json");
    if std::env::var_os("RSE_BLESS").is_some() {
        // As the golden tables are kept: written anew, on purpose.
        std::fs::write(&seed, rse_fuzz::good_manifest()).unwrap();
        return;
    }
    assert!(
        std::fs::read(seed).unwrap() == rse_fuzz::good_manifest(),
        "fuzz/seeds/manifest/good.json is stale: write it anew with RSE_BLESS=1 cargo test -p rse-fuzz --test replay"
    );
}
