# Sourced by scripts/wheel and scripts/dist: the environment of a reproducible build with zig
# (the same bytes from two builds of the same commit, wherever the checkout is).
# - SOURCE_DATE_EPOCH: the commit's time, for every timestamp (the wheel's zip entries).
# - --remap-path-prefix for the checkout, the target directory, cargo's registry and the Rust
#   toolchain, so that no path of this machine is in the binaries (panic messages hold source
#   paths); the dist profile builds without debug information and strips symbols.
# - The tools of scripts/build-tools first on the PATH: maturin, cargo-zigbuild, and python3 with
#   the ziglang package, which is how both find zig.
# Sets BIN (the tools' directory) and TARGET_DIR.
root=$(pwd)
BIN=$(scripts/build-tools)
export PATH="$BIN:$PATH"
if [ -z "${SOURCE_DATE_EPOCH:-}" ]; then
  SOURCE_DATE_EPOCH=$(git log -1 --format=%ct 2>/dev/null) || {
    echo "$(basename "$0"): not a git checkout: set SOURCE_DATE_EPOCH (seconds since 1970) for the build's timestamps" >&2
    exit 1
  }
fi
export SOURCE_DATE_EPOCH
TARGET_DIR=$(realpath -m "${CARGO_TARGET_DIR:-$root/target}")
cargo_home=$(realpath -m "${CARGO_HOME:-$HOME/.cargo}")
sysroot=$(rustc --print sysroot)
# rustc applies the last matching prefix: the target directory (perhaps inside the checkout)
# comes after the checkout.
RUSTFLAGS="--remap-path-prefix=$root=/stickslip --remap-path-prefix=$cargo_home=/cargo"
RUSTFLAGS+=" --remap-path-prefix=$sysroot=/rust --remap-path-prefix=$TARGET_DIR=/target"
export RUSTFLAGS
unset CARGO_ENCODED_RUSTFLAGS
