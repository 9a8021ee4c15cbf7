; Comments can carry TODO/FIXME notes.
((comment) @injection.content
  (#set! injection.language "comment"))
