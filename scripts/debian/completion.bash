# bash completion for rigsimd, rigsimctl and rigsim-replay (installed as
# /usr/share/bash-completion/completions/<program>). The flags, commands and actions are read from
# each program's own --help, so they cannot drift from it; plain bash (compgen), no helpers of the
# bash-completion package needed.

# The long flags a --help text names.
_rigsim_flags()
{
    "$@" --help 2>/dev/null | grep -o -- '--[a-z0-9][a-z0-9-]*' | sort -u
}

# The commands (or actions) an argparse help lists under its COMMAND (or ACTION) argument.
_rigsim_choices()
{
    "$@" --help 2>/dev/null | awk '/^  [A-Z]+$/ { on = 1; next } on && /^    [a-z]/ { print $1; next } /^[^ ]/ { on = 0 }' | tr '\n' ' '
}

_rigsimd()
{
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} IFS=$'\n'
    COMPREPLY=()
    case $prev in
        --config|--check-config|--endpoints-json|--state-file|--control-token-file)
            COMPREPLY=($(compgen -f -- "$cur")); return ;;
        --pty-dir)
            COMPREPLY=($(compgen -d -- "$cur")); return ;;
        --pty-group)
            COMPREPLY=($(compgen -g -- "$cur")); return ;;
        --log-level)
            COMPREPLY=($(compgen -W $'trace\ndebug\ninfo\nwarn\nerror\ncritical\noff' -- "$cur")); return ;;
        --control-token|--bind|--control|--control-allow-host|--max-connections|--max-connections-per-device|--time-scale|--tick-hz)
            return ;;
    esac
    COMPREPLY=($(compgen -W "$(_rigsim_flags "${COMP_WORDS[0]}")" -- "$cur"))
}

# rigsimctl [FLAGS] COMMAND [ACTION] [ARGS]: flags anywhere; a command, then its action, from the
# help of what is typed so far.
_rigsimctl()
{
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} IFS=$'\n'
    local -a path=("${COMP_WORDS[0]}")
    local i word
    COMPREPLY=()
    case $prev in
        --token-file|--endpoints)
            COMPREPLY=($(compgen -f -- "$cur")); return ;;
        --format)
            COMPREPLY=($(compgen -W $'json\ntable' -- "$cur")); return ;;
        --control|--token|--channel)
            return ;;
    esac
    for ((i = 1; i < COMP_CWORD; i++)); do
        word=${COMP_WORDS[i]}
        [[ $word == -* ]] && continue
        if [[ " $(_rigsim_choices "${path[@]}") " == *" $word "* ]]; then
            path+=("$word")
        fi
    done
    if [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W "$(_rigsim_flags "${path[@]}")" -- "$cur"))
    else
        IFS=' ' read -r -a words <<< "$(_rigsim_choices "${path[@]}")"
        IFS=$'\n' COMPREPLY=($(compgen -W "$(printf '%s\n' "${words[@]}")" -- "$cur"))
    fi
}

_rigsim_replay()
{
    local cur=${COMP_WORDS[COMP_CWORD]} IFS=$'\n'
    if [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W "$(_rigsim_flags "${COMP_WORDS[0]}")" -- "$cur"))
    else
        COMPREPLY=($(compgen -f -- "$cur"))
    fi
}

complete -o bashdefault -o default -F _rigsimd rigsimd
complete -o bashdefault -o default -F _rigsimctl rigsimctl
complete -o bashdefault -o default -F _rigsim_replay rigsim-replay
