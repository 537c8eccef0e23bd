# One warning policy for every target of the tree.
function(lpv_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wno-missing-field-initializers)
  if(LPV_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
