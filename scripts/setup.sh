# Sourced by scripts/view and .ci/run: installs what building, testing and viewing need on a
# fresh Debian machine (Rust from rustup, the Debian packages for Mesa's software Vulkan driver,
# X11 and Xvfb), and sets XDG_RUNTIME_DIR. Safe to source again: it only installs what is missing.

if ! command -v cargo >/dev/null 2>&1 && [ -f "$HOME/.cargo/env" ]; then
    . "$HOME/.cargo/env"
fi
if ! command -v cargo >/dev/null 2>&1; then
    echo "setup: installing Rust with rustup (https://rustup.rs)" >&2
    curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs |
        sh -s -- -y --profile minimal --component rustfmt,clippy
    . "$HOME/.cargo/env"
fi

# The GPU backend runs on Mesa's software Vulkan driver (lavapipe) where there is no GPU; the
# viewer's window needs the X11 client libraries, and its end-to-end test Xvfb (see
# ../shared/notes/stack.md for how these were found).
LUMIS_APT_PACKAGES=(
    build-essential pkg-config curl
    mesa-vulkan-drivers libvulkan1 libegl1 libegl-mesa0 libgl1-mesa-dri
    xvfb xauth libx11-6 libx11-xcb1 libxcursor1 libxi6 libxrandr2 libxkbcommon0 libxkbcommon-x11-0
    libfontconfig1
)
lumis_missing=()
for p in "${LUMIS_APT_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || lumis_missing+=("$p")
done
if [ ${#lumis_missing[@]} -gt 0 ]; then
    echo "setup: installing Debian packages: ${lumis_missing[*]}" >&2
    lumis_sudo=""
    [ "$(id -u)" -ne 0 ] && lumis_sudo="sudo"
    $lumis_sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $lumis_sudo apt-get install -y -qq "${lumis_missing[@]}"
fi

# Mesa and winit complain without a runtime dir; any private directory will do.
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "$XDG_RUNTIME_DIR" ]; then
    XDG_RUNTIME_DIR="$(mktemp -d)"
    chmod 700 "$XDG_RUNTIME_DIR"
    export XDG_RUNTIME_DIR
fi
