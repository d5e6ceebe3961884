# What `cmake --install` puts where (GNU layout; the .deb installs under /usr):
#   bin/seqc                                  the tool
#   share/seqc/seqc.schema.json               the language's JSON Schema, for editors
#   share/doc/seqc/examples/*.yaml            the examples; README, copyright (the LICENSE),
#                                             CHANGELOG
#   share/man/man1/seqc.1.gz                  generated from the same text as --help
#   share/bash-completion/completions/seqc    bash, zsh and fish completion, generated likewise;
#   share/zsh/vendor-completions/_seqc        zsh looks in vendor-completions under /usr and in
#     (or share/zsh/site-functions/_seqc)     site-functions under any other prefix (/usr/local)
#   share/fish/vendor_completions.d/seqc.fish
#   lib/udev/rules.d/70-seqc.rules            device access (uaccess; plugdev/dialout fallback)
include(GNUInstallDirs)

install(TARGETS seqc RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES schemas/seqc.schema.json DESTINATION ${CMAKE_INSTALL_DATADIR}/seqc)
# Also beside the examples, so their modeline ($schema=../schemas/seqc.schema.json) works there.
install(FILES schemas/seqc.schema.json DESTINATION ${CMAKE_INSTALL_DOCDIR}/schemas)
install(DIRECTORY examples/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples
        FILES_MATCHING PATTERN "*.yaml")
install(FILES README.md CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)
install(FILES ${SEQC_GENERATED_DOCS}/seqc.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${SEQC_GENERATED_DOCS}/seqc.bash
        DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions RENAME seqc)
# The prefix is known only when installing (`cmake --install --prefix`), so the choice is made then.
install(CODE "
  if(CMAKE_INSTALL_PREFIX STREQUAL \"/usr\")
    set(seqc_zsh_dir vendor-completions)
  else()
    set(seqc_zsh_dir site-functions)
  endif()
  file(INSTALL \"${SEQC_GENERATED_DOCS}/_seqc\"
       DESTINATION \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/zsh/\${seqc_zsh_dir}\")
")
install(FILES ${SEQC_GENERATED_DOCS}/seqc.fish
        DESTINATION ${CMAKE_INSTALL_DATADIR}/fish/vendor_completions.d)
# udev reads rules from /usr/lib/udev/rules.d (and /etc/udev/rules.d), not from /usr/local: a
# prefix other than /usr installs the rule where `sudo cp` can find it (docs/ports.md).
install(FILES scripts/udev/70-seqc.rules DESTINATION lib/udev/rules.d)
