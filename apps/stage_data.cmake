# Copies ladarsim's run-time data from the source tree (SOURCE) into DEST, in the layout the program
# reads beside itself (<exe_dir>/../share/ladarsim, data_dir.h) and `cmake --install` installs as
# it is:
#   scripts/              the plot scripts (eval, table1 and bench --plot, preview, campaign's card)
#   viewer/               the page `view` serves, with the three.js files it imports
#   scenarios/, models/   the bundled scenarios (bench's default) and the models they name
#   campaigns/            the bundled campaign specs (their models are ../models/)
#   classifiers/          the bundled track classifier (`detect`'s default), trained on campaigns/classes.json
# file(COPY) skips a file whose copy bears its timestamp: a build copies only what changed.
foreach(script preview plot_eval plot_table1 plot_bench plot_campaign)
  file(COPY ${SOURCE}/scripts/${script}.py DESTINATION ${DEST}/scripts)
endforeach()
file(COPY ${SOURCE}/apps/viewer/index.html ${SOURCE}/apps/viewer/viewer.js DESTINATION ${DEST}/viewer)

# three.js as scripts/setup.sh installs it (pinned in apps/viewer/package-lock.json): the module and
# the one addon viewer.js imports, with its licence. Without it `view` says what to run.
set(three ${SOURCE}/apps/viewer/node_modules/three)
foreach(file build/three.module.js examples/jsm/controls/OrbitControls.js LICENSE)
  if(EXISTS ${three}/${file})
    get_filename_component(dir ${file} DIRECTORY)
    file(COPY ${three}/${file} DESTINATION ${DEST}/viewer/node_modules/three/${dir})
  endif()
endforeach()

# Scenarios over a recorded map (*-autzen) stay out: their map lies beside a checkout (../shared).
file(GLOB scenarios ${SOURCE}/assets/scenarios/*.json)
list(FILTER scenarios EXCLUDE REGEX "-autzen\\.json$")
file(COPY ${scenarios} DESTINATION ${DEST}/scenarios)
file(COPY ${SOURCE}/assets/models/ DESTINATION ${DEST}/models)
file(COPY ${SOURCE}/assets/campaigns/ DESTINATION ${DEST}/campaigns)
file(COPY ${SOURCE}/assets/classifiers/ DESTINATION ${DEST}/classifiers)
