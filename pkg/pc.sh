#!/bin/sh
# pc.sh PREFIX LIBDIR INCLUDEDIR VERSION PRIVATE_LIBS -- irrcache.pc on
# stdout (make writes build/irrcache.pc).  Directories under PREFIX are
# written relative to ${prefix}, so `pkg-config --define-prefix` and
# PKG_CONFIG_SYSROOT_DIR both find a staged (DESTDIR) tree.
set -eu
prefix=$1 libdir=$2 includedir=$3 version=$4
private=$(echo $5)
rel() {
    case $1 in
    "$prefix"/*) printf '${prefix}/%s' "${1#"$prefix"/}" ;;
    *) printf '%s' "$1" ;;
    esac
}
cat <<PC
prefix=$prefix
libdir=$(rel "$libdir")
includedir=$(rel "$includedir")

Name: irrcache
Description: Irradiance and SH radiance cache with gradients, in the caller's memory
Version: $version
Libs: -L\${libdir} -lirrcache
Libs.private: $private
Cflags: -I\${includedir}
PC
