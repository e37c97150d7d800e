#!/bin/sh
# The repository speaks of the product alone: fails, listing the lines, when a tracked file names
# how the work on it was organised (work-stop labels, sessions, engineers, coordinators, worktrees,
# a local timing wrapper, issue numbers) rather than the product. History belongs in git's log.
#   tools/check_words.sh        check every tracked file (from the repository's root)
#   tools/check_words.sh -      check standard input instead (the suite checks that it catches them)
set -eu
pattern='\b([a-z]+(st|nd|rd|th)|this|last|next|that|earlier|previous|each|every) stop\b|\bsessions?\b|engineers?\b|coordinators?\b|worktrees?\b|cpu-timing|\bissues? #?[0-9]+\b'
if [ "${1:-}" = "-" ]; then
  if grep -n -i -E "$pattern"; then exit 1; fi
  exit 0
fi
cd "$(dirname "$0")/.."
# This file holds the pattern itself; images and other binary files hold no words.
if git grep -n -I -i -E "$pattern" -- . ':!tools/check_words.sh'; then
  echo "check_words: the lines above speak of how the work was organised, not of the product" >&2
  exit 1
fi
