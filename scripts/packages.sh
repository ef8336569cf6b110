# Sourced by scripts/setup.sh and scripts/fuzz.sh: install_missing_packages PACKAGE... installs, with
# apt-get, those of the named Debian packages that are not installed yet (nothing when all are: safe to
# run again), as root or through sudo.
install_missing_packages() {
  local missing=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]} == 0)); then
    echo "packages: all present ($*)"
    return 0
  fi
  echo "packages: installing missing Debian packages: ${missing[*]}"
  local sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
}
