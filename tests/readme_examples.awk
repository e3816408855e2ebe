# Collects the ```sh blocks between README.md's `<!-- examples:start -->` and
# `<!-- examples:end -->` markers into the file `out`, each announced by an
# `echo "--- example N (README.md line L)"`, to run in order in one shell (later examples
# use variables set by earlier ones). Used by tests/curl_examples.sh and
# tests/compose/smoke.sh:
#
#   awk -v out=FILE -f tests/readme_examples.awk README.md
/<!-- examples:start -->/ { on = 1; next }
/<!-- examples:end -->/   { on = 0; next }
on && /^```sh$/ { inblock = 1; n++; printf "echo \"--- example %d (README.md line %d)\"\n", n, NR + 1 >> out; next }
on && inblock && /^```$/ { inblock = 0; print "echo" >> out; next }
on && inblock { print >> out }
