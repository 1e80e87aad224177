#!/bin/sh
# Counts what a program that includes thintool/thintool.h sees of ThinTool: the headers it pulls
# in, the types they define (struct, class, enum and alias definitions; the exported classes,
# written `class THINTOOL_API Name`, are counted apart) and the free functions they declare at
# namespace level (lines that open a declaration at column 0). Regular expressions over the
# headers, not a parser: the counts compare trees, they are no exact census.
#
#   ./scripts/api-surface.sh [source tree, . by default]
set -eu
tree=${1:-.}
cd "$tree"
headers=$(echo '#include <thintool/thintool.h>' |
  g++ -std=c++17 -Iinclude -Isrc $(pkg-config --cflags bullet) -x c++ -M - |
  tr ' \\' '\n\n' | grep '/thintool/' | sort -u)
echo "headers: $(echo "$headers" | wc -l)"
types=$(cat $headers | grep -oE '^\s*(struct|class|enum class|enum|using) [A-Za-z0-9_]+( final)?( :[^;{]*)?( \{| =)' |
  sed -E 's/^\s*(enum class|struct|class|enum|using) //; s/[ :={].*//' | sort -u)
echo "types: $(echo "$types" | wc -l)"
echo "$types" | tr '\n' ' '; echo
exported=$(cat $headers | grep -oE '^class THINTOOL_API [A-Za-z0-9_]+' | awk '{print $3}' | sort -u)
echo "exported classes: $(echo "$exported" | wc -l)"
echo "$exported" | tr '\n' ' '; echo
functions=$(cat $headers |
  grep -E '^(THINTOOL_API |inline |constexpr |template.*)?[A-Za-z_:<>,& ]+[ &*]([a-z][A-Za-z0-9_]*)\(' |
  grep -vE '^[[:space:]]|^(class|struct|return|if|for|namespace)' | sed -E 's/\(.*//' | awk '{print $NF}' | tr -d '&*' | sort -u)
echo "free functions: $(echo "$functions" | wc -l)"
echo "$functions" | tr '\n' ' '; echo
