cmake_minimum_required(VERSION 3.20)  # script mode: if(IN_LIST)
# Runs a bad deck and checks that sable fails with the message its first line promises:
#   # expect: FILE:LINE: TEXT
# FILE:LINE is where the error must point (the deck's own name, or an included or data
# file's), TEXT a piece of the message after that location. TEXT may not be a piece of
# any command line of the deck and must hold a word the deck's commands do not, so the
# quoted command in the message cannot meet it alone.
# A failed check prints its reason unwrapped (FATAL_ERROR re-wraps text), whole for a
# reader and for the regexes of tests/decks/bad_controls, then stops.
function(fail_check msg)
  message(NOTICE "${msg}")
  message(FATAL_ERROR "the bad-deck check failed")
endfunction()

file(STRINGS ${DECK} lines)
list(GET lines 0 first)
if(NOT first MATCHES "^# *expect: *([^: ]+):([0-9]+): *(.+)$")
  fail_check("deck ${DECK}: the first line must read '# expect: FILE:LINE: text', not '${first}'")
endif()
set(loc "${CMAKE_MATCH_1}:${CMAKE_MATCH_2}:")
set(expected "${CMAKE_MATCH_3}")
string(STRIP "${expected}" expected)
string(LENGTH "${expected}" n)
if(n LESS 4)
  fail_check("deck ${DECK}: the expected text '${expected}' is too short to name an error")
endif()
# The deck's commands (lines that are not wholly comments: a message may quote its line,
# trailing comment and all, but never a comment line).
set(body "")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^[ \t]*#")
    list(APPEND body "${line}")
  endif()
endforeach()
foreach(line IN LISTS body)
  string(FIND "${line}" "${expected}" in_deck)
  if(NOT in_deck EQUAL -1)
    fail_check("deck ${DECK}: the expected text '${expected}' is part of the deck line '${line}': "
              "the echoed command would meet it; expect words only the error message has")
  endif()
endforeach()
# ... and at least one word of it (three letters or more) must be absent from the commands.
string(REGEX MATCHALL "[A-Za-z][A-Za-z][A-Za-z]+" deck_words "${body}")
string(REGEX MATCHALL "[A-Za-z][A-Za-z][A-Za-z]+" words "${expected}")
set(own_word "")
foreach(w IN LISTS words)
  if(NOT w IN_LIST deck_words)
    set(own_word "${w}")
    break()
  endif()
endforeach()
if(own_word STREQUAL "")
  fail_check("deck ${DECK}: every word of the expected text '${expected}' is in the deck's commands; "
              "expect a word only the error message has")
endif()

execute_process(COMMAND ${SABLE} -in ${DECK} -log none -echo none RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  fail_check("deck ${DECK} should have failed but exited 0\n${out}")
endif()
# The location as a whole file name: after a '/', a space, a quote or at the start.
set(at -1)
foreach(pre "/" " " "'" "\n")
  string(FIND "${pre}${err}" "${pre}${loc}" at)
  if(NOT at EQUAL -1)
    break()
  endif()
endforeach()
if(at EQUAL -1)
  fail_check("deck ${DECK}: expected an error located at '${loc}', got:\n${err}")
endif()
string(LENGTH "${pre}${loc}" loc_len)
math(EXPR after "${at} + ${loc_len}")
string(SUBSTRING "${pre}${err}" ${after} -1 message_text)
string(FIND "${message_text}" "${expected}" found)
if(found EQUAL -1)
  fail_check("deck ${DECK}: expected an error at '${loc}' containing '${expected}', got:\n${err}")
endif()
message(STATUS "failed as expected: ${err}")
