# Sourced by the test scripts: `cached_venv LINK PYTHON INSTALL FILE...`
# makes LINK (e.g. .venv-frameworks) a symbolic link to a virtual
# environment kept outside the clone, in a cache keyed by FILE... (the
# pinned requirements it is made from) and PYTHON's version, so that every
# fresh clone on this machine (CI clones main anew for each run) reuses it.
#
# - A venv is made at its final path (venvs are not relocatable: their
#   scripts name it) by `python -m venv`, then the shell function INSTALL
#   runs with the venv's python as $1; the marker `.rse-ready` is written
#   last, so an interrupted install is made again, never half-used.
# - A changed pin changes the key: the new venv is made, and the older
#   venvs of the same LINK name are removed once it is ready, so the disk
#   holds one venv per name (the framework venvs weigh some 25 GB).
# - One process at a time per name (flock): two runs of the tests on one
#   machine wait for each other instead of installing into the same folder.
#
# The cache is $RSE_VENV_CACHE, default ${XDG_CACHE_HOME:-~/.cache}/rse/venvs.

cached_venv() {
    local link=$1 python=$2 install=$3
    shift 3
    local cache=${RSE_VENV_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/rse/venvs}
    local name
    name=$(basename "$link")
    name=${name#.}
    local key
    key=$(
        {
            "$python" -c 'import sys; print(sys.version)'
            for file in "$@"; do
                printf '%s\n' "$file"
                cat "$file"
            done
            # How the venv is made is part of the key too.
            declare -f "$install"
        } | sha256sum | cut -c1-16
    )
    local dir="$cache/$name-$key"
    mkdir -p "$cache"
    (
        flock 9
        if [ ! -e "$dir/.rse-ready" ]; then
            printf '\n== making the venv %s (%s, kept in %s)\n' "$link" "$*" "$cache" >&2
            rm -rf "$dir"
            "$python" -m venv "$dir"
            "$install" "$dir/bin/python"
            touch "$dir/.rse-ready"
        fi
        # The older venvs of this name: a pin changed since they were made.
        for old in "$cache/$name"-*; do
            if [[ $(basename "$old") =~ ^$name-[0-9a-f]{16}$ ]] && [ "$old" != "$dir" ]; then
                printf '== removing %s (its pins are gone)\n' "$old" >&2
                rm -rf "$old"
            fi
        done
        # A venv made in the clone by an older version of these scripts is
        # replaced by the link (under the lock: two runs may link at once).
        if [ -d "$link" ] && [ ! -L "$link" ]; then
            rm -rf "$link"
        fi
        ln -sfn "$dir" "$link"
    ) 9>"$cache/$name.lock"
}

# `pip_install PYTHON ARGS...`: pip install, quietly, as every script does.
pip_install() {
    local python=$1
    shift
    "$python" -m pip install --quiet --disable-pip-version-check "$@"
}
