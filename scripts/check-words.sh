#!/usr/bin/env bash
# Fails when a tracked text file (source, test, script, doc, README, bench page) speaks of an
# issue, session or turn number ("issue 20", "issues 15/17", "session-10", "Turn 3"): those are
# tracker and work-log numbers a reader of the code cannot look up; history belongs in commit
# messages. Lists each offending file:line.
# Not searched: binary files (git grep -I: images, streams, fuzz corpora), and this script,
# which has to spell the pattern out. A name such as bench/results/rd_issue20.md does not
# match ("_" joins it to the word before), so links to such files stay allowed.
set -euo pipefail
cd "$(dirname "$0")/.."
pattern='\b(issue|session|turn)s?[ _-]?#?[0-9]'
if hits=$(git grep -nIiE "$pattern" -- . ':!scripts/check-words.sh'); then
  echo "check-words: issue/session/turn numbers in tracked files (say what the code does instead):"
  printf '%s\n' "$hits" | sed 's/^/  /'
  exit 1
fi
echo "check-words: no issue, session or turn numbers"
