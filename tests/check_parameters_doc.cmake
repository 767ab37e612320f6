# docs/parameters.md must be what `pcsketch parameters --markdown` writes from the option table.
execute_process(COMMAND ${CLI} parameters --markdown OUTPUT_VARIABLE generated RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "pcsketch parameters --markdown failed (${status})")
endif()
file(READ ${DOC} checked_in)
if(NOT generated STREQUAL checked_in)
  message(FATAL_ERROR "docs/parameters.md is out of date: run `pcsketch parameters --markdown > docs/parameters.md`")
endif()
