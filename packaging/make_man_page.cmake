# Writes fetic's man page (section 1) from the help texts of the program it was built
# into: `fetic --help`, then `fetic help COMMAND` for every command. Run at build time
# (cmake/FeticInstall.cmake), so the page cannot fall behind the options.
#   cmake -DFETIC=path/to/fetic -DOUT=fetic.1 -DVERSION=0.1.0 -P make_man_page.cmake

# roff: a backslash is written \e; a line starting with . or ' is escaped by \&.
function(roff_text text out)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

function(help_of arguments out)
  execute_process(COMMAND ${FETIC} ${arguments} OUTPUT_VARIABLE text RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${FETIC} ${arguments} failed (${status})")
  endif()
  string(REPLACE "${FETIC}" "fetic" text "${text}")  # the usage line names argv[0]
  roff_text("${text}" text)
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

help_of("--help" program)
# The commands: the lines of the Subcommands section, "  NAME   description", up to the
# blank line that ends it.
string(REGEX MATCH "[Ss][Uu][Bb][Cc][Oo][Mm][Mm][Aa][Nn][Dd][Ss]:\n([^\n]+\n)+" commands_block
       "${program}")
string(REGEX MATCHALL "\n  [a-z-]+" command_lines "${commands_block}")
if(NOT command_lines)
  message(FATAL_ERROR "no commands found in `${FETIC} --help`")
endif()
set(page ".TH FETIC 1 \"\" \"fetic ${VERSION}\" \"User Commands\"\n")
string(APPEND page ".SH NAME\nfetic \\- frictionless contact of elastic struts (bar, plane stress, frames) by FETI and FETI-C\n")
string(APPEND page ".SH SYNOPSIS\n.B fetic\n.I COMMAND\n[\n.I OPTIONS\n]\n")
string(APPEND page ".SH DESCRIPTION\n.nf\n${program}.fi\n")
foreach(line IN LISTS command_lines)
  string(STRIP "${line}" command)
  help_of("help;${command}" text)
  string(TOUPPER "${command}" title)
  string(APPEND page ".SH \"FETIC ${title}\"\n.nf\n${text}.fi\n")
endforeach()
string(APPEND page ".SH FILES\n.TP\n.I /usr/share/fetic/scenes\nthe bundled scenes (\\fBfetic scenes\\fR lists them; give one by name, e.g. \\fBfetic solve thesis\\fR)\n")
string(APPEND page ".TP\n.I /usr/share/doc/fetic\nREADME.md and docs/ (the scene and result file contract: docs/SCENES.md)\n")
file(WRITE "${OUT}" "${page}")
