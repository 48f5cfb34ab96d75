#!/bin/sh
# Regenerate the pictures of docs/reproducing-the-paper.md:
# runs `crane` on the scenarios in examples/ and copies the SVGs picked for
# each paper figure into docs/figures/.
#   sh docs/figures/make.sh
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
dest=docs/figures
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cargo build --quiet --release --bin crane
crane() { cargo run --quiet --release --bin crane -- "$@"; }
run() { # run OUT MODEL SCENARIO [FLAGS...]: crane run into $work/OUT
    out=$1 model=$2 scenario=$3
    shift 3
    crane run "$model" --scenario "examples/$scenario" --out "$work/$out" --quiet "$@" >/dev/null
}
pick() { # pick OUT FILE NAME: copy $work/OUT/FILE to docs/figures/NAME
    cp "$work/$1/$2" "$dest/$3"
}

# Planar crane, massless pulley (sect. 5.1): Figs. 5, 6, 7, 9, 10
run planar-0.1 navy-planar navy-planar-fig5-8.toml --dt 0.1
run planar-0.01 navy-planar navy-planar-fig5-8.toml --dt 0.01
run planar-15 navy-planar navy-planar-fig9.toml --dt 0.1
crane convergence navy-planar --scenario examples/navy-planar-fig5-8.toml --out "$work/planar-conv" >/dev/null
pick planar-0.1 coordinates.svg fig05-planar-coordinates-dt0.1.svg
pick planar-0.1 inputs.svg fig06-planar-inputs-dt0.1.svg
pick planar-0.01 inputs.svg fig06-planar-inputs-dt0.01.svg
pick planar-conv convergence.svg fig07-planar-convergence.svg
pick planar-0.01 multipliers.svg fig07-planar-multipliers-dt0.01.svg
pick planar-15 coordinates.svg fig09-planar-coordinates-tf15.svg
pick planar-15 inputs.svg fig09-planar-inputs-tf15.svg
pick planar-0.01 snapshots.svg fig10-planar-snapshots.svg

# Planar crane with pulley mass (sect. 5.2): Figs. 14, 15, 16, 18, 19
run pulley-0.1 navy-planar-pulley navy-planar-pulley-fig14-17.toml --dt 0.1
run pulley-0.01 navy-planar-pulley navy-planar-pulley-fig14-17.toml --dt 0.01
run pulley-15 navy-planar-pulley navy-planar-pulley-fig18.toml --dt 0.1
crane convergence navy-planar-pulley --scenario examples/navy-planar-pulley-fig14-17.toml --out "$work/pulley-conv" >/dev/null
pick pulley-0.1 coordinates.svg fig14-pulley-coordinates-dt0.1.svg
pick pulley-0.1 inputs.svg fig15-pulley-inputs-dt0.1.svg
pick pulley-0.01 inputs.svg fig15-pulley-inputs-dt0.01.svg
pick pulley-conv convergence.svg fig16-pulley-convergence.svg
pick pulley-0.01 multipliers.svg fig16-pulley-multipliers-dt0.01.svg
pick pulley-15 coordinates.svg fig18-pulley-coordinates-tf15.svg
pick pulley-15 inputs.svg fig18-pulley-inputs-tf15.svg
pick pulley-0.01 snapshots.svg fig19-pulley-snapshots.svg

# 3D crane, massless pulley (sect. 6.1): Figs. 22, 23
run 3d navy-3d navy-3d-fig22-23.toml --dt 0.01
pick 3d coordinates.svg fig22-3d-coordinates.svg
pick 3d inputs.svg fig22-3d-inputs.svg
pick 3d snapshots.svg fig23-3d-snapshots.svg

# 3D crane with pulley mass (sect. 6.2): Figs. 25, 26, and the smooth profile
run 3dp navy-3d-pulley navy-3d-pulley-fig25-26.toml --dt 0.1
run 3dp-0.01 navy-3d-pulley navy-3d-pulley-fig25-26.toml --dt 0.01
run 3dp-smooth navy-3d-pulley navy-3d-pulley-smooth.toml --dt 0.01
pick 3dp inputs.svg fig25-3d-pulley-inputs-dt0.1.svg
pick 3dp-0.01 inputs.svg fig25-3d-pulley-inputs-dt0.01.svg
pick 3dp-smooth inputs.svg fig25-3d-pulley-inputs-smooth.svg
pick 3dp snapshots.svg fig26-3d-pulley-snapshots.svg

du -ch "$dest"/*.svg | tail -1

# Beyond the paper: the BDF-4 torques of the pulley crane replayed on a
# 10 % heavier load, open loop and with the default feedback ("Does the
# computed input work?")
crane run navy-planar-pulley --scheme bdf4 --replay --settle 9 --plant m_l=110 --feedback default --out "$work/replay" --quiet >/dev/null
pick replay replay.svg replay-pulley-heavier-load.svg

# Stable inversion (docs/internal-dynamics.md): the coupled trolley's bounded
# inputs against its causal ones
crane run coupled-trolley --out "$work/coupled-stable" --quiet >/dev/null
crane run coupled-trolley --formulation redundant --out "$work/coupled-causal" --quiet >/dev/null 2>&1
pick coupled-stable inputs.svg coupled-trolley-stable-inputs.svg
pick coupled-causal inputs.svg coupled-trolley-causal-inputs.svg
