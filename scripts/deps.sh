# Sourced by the scripts: installs the Debian packages the build needs, if missing.
ensure_packages() {
    local missing=()
    for package in "$@"; do
        dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    echo "actionstring: installing missing Debian packages: ${missing[*]}" >&2
    local sudo=""
    if [ "$(id -u)" -ne 0 ]; then
        if command -v sudo >/dev/null 2>&1; then
            sudo="sudo"
        else
            echo "actionstring: not root and no sudo; install these packages first: ${missing[*]}" >&2
            return 1
        fi
    fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# Packages for building and testing on the host, and for the Cortex-M builds.
ACTIONSTRING_HOST_PACKAGES=(cmake make g++ clang libclang-rt-14-dev libeigen3-dev doctest-dev jq mono-mcs mono-runtime
                            python3-dev python3-venv python3-pip python3-setuptools python3-wheel pybind11-dev
                            python3-numpy python3-pytest python3-sklearn chromium fonts-dejavu-core
                            gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib
                            qemu-system-arm)
