# Sourced by scripts to parse their options, with the conventions of Kaldi's utils/parse_options.sh
# (egs/wsj/s5/utils/parse_options.sh), for machines without Kaldi. run.sh sources Kaldi's own file
# when KALDI_ROOT is set, so a script behaves the same with either.
#
#   --name value       sets the shell variable name (dashes become underscores); the variable must
#                      already be defined by the script (its default), else the option is an error.
#                      A variable whose default is true or false only accepts true or false.
#   --config file      sources a file of name=value lines first (Kaldi's --config).
#   --help, -h         prints $help_message and exits 0.
#   --name=value       is an error, as in Kaldi ("options must be of the form --name value").
# Parsing stops at the first argument that does not start with "--"; the remaining arguments are
# left in "$@" for the script.

# Kaldi sources every --config file among the options before parsing the rest (the option is then
# also parsed below, setting $config).
__po_i=1
while [ $__po_i -lt $# ]; do
  if [ "${!__po_i}" = "--config" ]; then
    __po_j=$((__po_i + 1))
    config=${!__po_j}
    if [ ! -r "$config" ]; then echo "$0: missing config '$config'" >&2; exit 1; fi
    # shellcheck disable=SC1090
    . "$config" || { echo "$0: error in config file $config" >&2; exit 1; }
  fi
  __po_i=$((__po_i + 1))
done
unset __po_i __po_j

while true; do
  [ -z "${1:-}" ] && break
  case "$1" in
    --help|-h)
      if [ -z "${help_message:-}" ]; then echo "No help found." >&2; else printf "%s\n" "$help_message" >&2; fi
      exit 0 ;;
    --*=*)
      echo "$0: options to scripts must be of the form --name value, got '$1'" >&2
      exit 1 ;;
    --*)
      __po_name=$(echo "$1" | sed 's/^--//; s/-/_/g')
      case "$__po_name" in
        ''|[0-9]*|*[!A-Za-z0-9_]*)
          echo "$0: invalid option $1" >&2; exit 1 ;;
      esac
      # The variable must exist (Kaldi's test: [ -z "${name+xxx}" ] means undefined).
      eval '[ -z "${'"$__po_name"'+xxx}" ]' && { echo "$0: invalid option $1" >&2; exit 1; }
      if [ $# -lt 2 ]; then
        echo "$0: option $1 needs a value" >&2
        exit 1
      fi
      __po_old=$(eval echo '"${'"$__po_name"'}"')
      if [ "$__po_old" = true ] || [ "$__po_old" = false ]; then
        if [ "$2" != true ] && [ "$2" != false ]; then
          echo "$0: expected \"true\" or \"false\": $1 $2" >&2
          exit 1
        fi
      fi
      eval "$__po_name=\"\$2\""
      shift 2 ;;
    *) break ;;
  esac
done
unset __po_name __po_old

# Kaldi's parse_options.sh leaves `set -e` semantics to the caller; it returns success.
true
