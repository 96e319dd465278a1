<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1">
<context>
    <name>@default</name>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="106"/>
        <source>The BirdsEye Processing provider could not be registered.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="115"/>
        <source>&amp;BirdsEye</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="117"/>
        <source>BirdsEye</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="120"/>
        <source>BirdsEye algorithms…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="122"/>
        <source>Open the Processing toolbox showing the BirdsEye algorithms</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="180"/>
        <source>The Processing plugin is not active: enable it under Plugins ▸ Manage and Install Plugins, then try again.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="210"/>
        <source>The &apos;{title}&apos; panel could not be opened ({module}.{cls}: {error}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="275"/>
        <source>Review clusters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="354"/>
        <source>Review setup</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="358"/>
        <source>choose one or more detection layers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="359"/>
        <source>Outputs of Detect targets over one flight (several checkpoints or thresholds are reviewed together: one verdict per spot).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="361"/>
        <source>Detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="365"/>
        <source>The flight&apos;s frame layer (Import flight log or Import DJI images): poses, camera and image of every frame.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="367"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="371"/>
        <source>The survey points (Import geotags).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="372"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="377"/>
        <source>GeoPackage holding the append-only verdict log (table birdseye_verdicts). Default: the first detection layer&apos;s GeoPackage, else one next to the project.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="380"/>
        <source>Verdict log</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="382"/>
        <source>Recorded with every verdict.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="384"/>
        <source>Reviewer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="386"/>
        <source>Clustering and matching</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="396"/>
        <source>DBSCAN minimum points per neighbourhood (itself included).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="407"/>
        <source>Size of the image window cut around a detection.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="414"/>
        <source>Map scale the canvas zooms to around each unit.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="415"/>
        <source>Grid cell</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="415"/>
        <source>EPS</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="415"/>
        <source>Min. points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="415"/>
        <source>EPS_PRED</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="415"/>
        <source>Edge buffer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="415"/>
        <source>Chip window</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="415"/>
        <source>Map scale</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="421"/>
        <source>Start / resume review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="444"/>
        <source>No review started</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="454"/>
        <source>All layers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="464"/>
        <source>Fired by</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="466"/>
        <source>Show</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="504"/>
        <source>Previous (P)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="506"/>
        <source>Next (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="523"/>
        <source>Undo (Ctrl+Z)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="525"/>
        <source>Add missed target (A)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="531"/>
        <source>Propagate to units within {:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="532"/>
        <source>Off by default. When on, a verdict also votes (provenance propagated:{rule}) on the units chained to this one by gaps of at most {eps:.2f} m; conflicting votes are resolved under the three conventions, all shown.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="537"/>
        <source>Next unit after a verdict</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="544"/>
        <source>&lt;b&gt;Scores per detection layer&lt;/b&gt; — after review under each tie-break convention</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="546"/>
        <source>Recall and the geotag-matched cluster fraction (GMCF), computed as Evaluate detections computes them from this verdict log.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="550"/>
        <source>before
review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="554"/>
        <source>After review, {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="568"/>
        <source>GMCF is a lower bound on precision, not precision; recall after review is an upper bound (≥). The spread between the conventions is part of the result.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="626"/>
        <source>Choose at least one detection layer (an output of Detect targets).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="631"/>
        <source>Choose a GeoPackage for the verdict log (save the project first to get one next to it).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="683"/>
        <source>{n} units from {k} layer(s); verdict log {path}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="768"/>
        <source>A layer of the review was removed from the project; the review stopped. Every verdict is in the log; choose the layers again to resume.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="826"/>
        <source>Added target</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="854"/>
        <source>&lt;b&gt;{pos}&lt;/b&gt; of {vis} shown · {done} of {n} units reviewed · {added} added</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="915"/>
        <source>An added target can only be withdrawn (0 or Backspace) or undone.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="926"/>
        <source>Saved: {key} → {verdict}{more} ({time} UTC)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="926"/>
        <source>, {} propagated vote(s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="941"/>
        <source>Nothing to undo.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="945"/>
        <source>Undone: action {action} on {key} (rows appended; nothing deleted).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="963"/>
        <source>The verdict was NOT saved: {error}. Check that {path} is writable and not locked, then try again.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="980"/>
        <source>Click the map where the missed target is (Esc or right click cancels).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1005"/>
        <source>Added target {key} (Ctrl+Z undoes it).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1005"/>
        <source>A target is already recorded there.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1026"/>
        <source>No units: the detection layers have no clusters at these settings.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1027"/>
        <source>Nothing to show</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1038"/>
        <source>Loading frames…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1045"/>
        <source>&lt;b&gt;Added target&lt;/b&gt; {key}&lt;br&gt;{lat:.7f}°, {lon:.7f}° · recorded as a target the detector missed (the &lt;i&gt;a&lt;/i&gt; term). 0 withdraws it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1052"/>
        <source>geotag {ids} within {eps:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1052"/>
        <source>no geotag within {eps:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1059"/>
        <source>none yet</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1060"/>
        <source>the conventions disagree</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1132"/>
        <source>The frames could not be read: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1134"/>
        <source>No frame of the frame layer shows this spot.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1140"/>
        <source>frame {f}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1147"/>
        <source>{shown} of {n} frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1181"/>
        <source>updating…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1190"/>
        <source>Scores could not be computed: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1205"/>
        <source>recall</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1207"/>
        <source>GMCF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1237"/>
        <source>Review verdicts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1256"/>
        <source>Cannot start the review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review_dock.py" line="1256"/>
        <source>Inputs changed since verdicts were recorded</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="112"/>
        <source>Accept</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="112"/>
        <source>Reject</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="112"/>
        <source>: κ* = λ_target / sup; every variance of the budget may grow by this factor. Accept when κ* ≥ 1.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="135"/>
        <source>Sensor-bound calculator</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="172"/>
        <source>Camera</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="179"/>
        <source>A platform sets the camera and the pose-noise budget together.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="182"/>
        <source>Platform</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="185"/>
        <source>Camera calibration (Kalibr or OpenCV YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="186"/>
        <source>Load fx, fy, cx, cy and the image size from a Kalibr camchain or OpenCV YAML file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="189"/>
        <source>Calibration</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="203"/>
        <source>Width</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="204"/>
        <source>Height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="216"/>
        <source>Pose noise (1σ)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="236"/>
        <source>Label tolerance and altitudes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="241"/>
        <source>Label radius r at 3σ: the label must stay within r px of the target.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="245"/>
        <source>σ_label = r/3: the Gaussian sigma of the soft labels (λ_target = σ_label²).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="249"/>
        <source>Tolerance r (3σ)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="251"/>
        <source>e.g. 10, 20</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="252"/>
        <source>Heights above the ground in metres, separated by commas.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="254"/>
        <source>Altitudes [m]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="258"/>
        <source>Verdicts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="266"/>
        <source>Altitude</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="266"/>
        <source>sup tr Σ
[px²]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="266"/>
        <source>sup λmax
[px²]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="266"/>
        <source>κ* trace</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="266"/>
        <source>κ* exact</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="268"/>
        <source>Largest trace of the label covariance over the frame (the linear, pessimistic criterion).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="270"/>
        <source>Largest eigenvalue of the label covariance over the frame (the exact criterion).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="276"/>
        <source>Details for</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="278"/>
        <source>The altitude whose budget table and λ_max field are shown.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="286"/>
        <source>Your σ</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="286"/>
        <source>Balanced σ
(trace)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="286"/>
        <source>Balanced σ
(exact)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="286"/>
        <source>Share of
error</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="288"/>
        <source>The largest budget with no axis starved (maximum Σ log σ²) that meets the exact bound.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="290"/>
        <source>Each axis&apos;s share of the error of your budget at the worst pixel: improve the largest first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="315"/>
        <source>λ_max field — red: the tolerance λ_target</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="328"/>
        <source>Evaluate every pixel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="329"/>
        <source>Re-evaluate on the full-resolution grid (stride 1 px), as the Processing algorithm does by default.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="332"/>
        <source>Use σ_label in Write labels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="333"/>
        <source>Store σ_label = r/3 px in the project; Write labels uses it as its default label sigma (SIGMA_PX).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="336"/>
        <source>Run in Processing…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="337"/>
        <source>Open the Sensor bound algorithm with these values, to write the JSON results, the HTML report and the λ_max raster.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="358"/>
        <source>Altitudes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="435"/>
        <source>σ_label = {value:.2f} px</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="461"/>
        <source>every pixel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="461"/>
        <source>preview grid: every {s} px and the frame edges</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="466"/>
        <source>λ_target = (r/3)² = {lam:.4g} px² · {grid}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="485"/>
        <source>worst pixel ({u:.0f}, {v:.0f})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="503"/>
        <source>worst at ({u:.0f}, {v:.0f})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="532"/>
        <source>σ_label = {s:.2f} px stored in the project: Write labels will use it as its label sigma (project variable @birdseye_sigma_label_px).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>BirdsEyeAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/base.py" line="93"/>
        <source>Cancelled by the user.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ClusterDetections</name>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="146"/>
        <source>Detections (from Detect targets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="149"/>
        <source>Geotags (optional: fills matched_geotag_ids and hit)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="152"/>
        <source>Frames of the flight (optional: only in-view geotags can match)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="156"/>
        <source>Clusters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="158"/>
        <source>De-duplicated points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="168"/>
        <source>DETECTIONS: the detection layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="178"/>
        <source>The detection layer holds no detection with a position.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="227"/>
        <source>OUTPUT: the cluster layer cannot be created.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="249"/>
        <source>OUTPUT_POINTS: the point layer cannot be created.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>DemParametersMixin</name>
    <message>
        <location filename="../processing/dem_parameters.py" line="26"/>
        <source>Terrain model (DEM/DSM raster, projected CRS in metres; empty: level ground)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/dem_parameters.py" line="29"/>
        <source>DEM heights are measured from</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/dem_parameters.py" line="32"/>
        <source>Geoid undulation N at the site (m; ellipsoidal = MSL + N)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>DesignParametersMixin</name>
    <message>
        <location filename="../processing/design_parameters.py" line="129"/>
        <source>Camera calibration (Kalibr or OpenCV YAML; overrides the intrinsics below)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/design_parameters.py" line="144"/>
        <source>Pose sigmas, 1σ (x, y, z in metres; roll, pitch, yaw in degrees)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/design_parameters.py" line="149"/>
        <source>Altitudes above the ground [m], comma-separated</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/design_parameters.py" line="154"/>
        <source>Label tolerance r [px] (label radius at 3σ)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/design_parameters.py" line="171"/>
        <source>Camera from {file}: {w}×{h} px, fx {fx:.4f}, fy {fy:.4f}, cx {cx:.4f}, cy {cy:.4f} px (the typed intrinsics are ignored).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/design_parameters.py" line="182"/>
        <source>{name}: the focal length must be greater than 0 px, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/design_parameters.py" line="197"/>
        <source>{name}: the label tolerance must be greater than 0 px, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/design_parameters.py" line="204"/>
        <source>Cancelled by the user.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Detect</name>
    <message>
        <location filename="../processing/algorithms/detect.py" line="38"/>
        <source>Frames (from Import flight log or Import DJI images)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="41"/>
        <source>ONNX heatmap model (empty: the bundled demo model)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="44"/>
        <source>Probability threshold (empty: the model&apos;s default)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="47"/>
        <source>Edge buffer (px): detections closer to the image border are dropped</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="51"/>
        <source>Detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="53"/>
        <source>Heatmap folder (one PNG per frame)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="59"/>
        <source>SHA-256 of the model</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="84"/>
        <source>FRAMES</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>EvaluateDetections</name>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="90"/>
        <source>Detection layers (one per flight)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="92"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="94"/>
        <source>Frame layers (one per flight, same order)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="97"/>
        <source>Review verdicts (optional: adds the POST scores)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="100"/>
        <source>Sealed selection rule (optional: verified, its operating point is used)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="103"/>
        <source>Scores (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="105"/>
        <source>Report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="116"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="119"/>
        <source>GEOTAGS: the layer holds no point with a position.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportDjiImages</name>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="23"/>
        <source>Folder of DJI images (JPEG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="25"/>
        <source>Camera calibration (optional; Kalibr or OpenCV YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="28"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="31"/>
        <source>DJI frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="33"/>
        <source>Frames written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="34"/>
        <source>Images that cannot be placed</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportFlightLog</name>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="23"/>
        <source>Pose log (BirdsEye CSV or flight_data.db)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="26"/>
        <source>Image folder (images.csv or &lt;sec&gt;.&lt;nsec&gt;.png|jpg files)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="29"/>
        <source>Camera calibration (Kalibr camchain or OpenCV YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="32"/>
        <source>Camera frame rate (frames/s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="35"/>
        <source>Minimum altimeter SNR (dB)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="37"/>
        <source>RTK filter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="39"/>
        <source>UTM zone of flight_data.db x, y (only for flight_data.db)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="41"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="44"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="46"/>
        <source>Flight line</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportGeotags</name>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="31"/>
        <source>Geotag file (rover CSV, CSV with header, NMEA)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="34"/>
        <source>…or a point layer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="36"/>
        <source>File format</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="40"/>
        <source>Fix filter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="42"/>
        <source>Antenna pole height (m), subtracted from heights</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="45"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="47"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="58"/>
        <source>Give either a geotag file (INPUT) or a point layer (INPUT_LAYER), not both and not neither.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="71"/>
        <source>The input holds no usable geotag.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="88"/>
        <source>No geotag is left to write (all were filtered out).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>MonteCarloBoundAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="48"/>
        <source>Monte Carlo samples</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="50"/>
        <source>Random seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="51"/>
        <source>Scaling study: smallest variance factor</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="53"/>
        <source>Scaling study: largest variance factor</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="55"/>
        <source>Scaling study: number of factors (log-spaced)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="57"/>
        <source>Scaling study per axis as well (7× the work)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="59"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="61"/>
        <source>Scaling-study plot (PNG, one panel per altitude)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="95"/>
        <source>{alt:g} m: max sKLD at the deployed budget {skld:.3g} nats over {n} test pixels (threshold {thr:g}) → the linearised bound {verdict}; exact κ* = {kappa:.3g}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="95"/>
        <source>holds</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="95"/>
        <source>does NOT hold</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="118"/>
        <source>{name}: the smallest variance factor must be greater than 0, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="121"/>
        <source>{name}: the largest variance factor must exceed {other} ({low:g}), got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>PlanFlight</name>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="40"/>
        <source>Geotags (point layer)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="42"/>
        <source>Selected geotags only</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="44"/>
        <source>Geotag id field (empty: &apos;id&apos; if present, else the feature number)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="47"/>
        <source>Home: take-off and landing point (optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="53"/>
        <source>Camera calibration (Kalibr or OpenCV YAML; optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="59"/>
        <source>Capture</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="69"/>
        <source>Plan even if the points spread over more than 10 km</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="73"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="77"/>
        <source>Waypoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="79"/>
        <source>Route</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="88"/>
        <source>Mission files written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="110"/>
        <source>GEOTAGS: the geotag layer could not be opened.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="114"/>
        <source>SELECTED_ONLY is set but no geotag of layer &apos;{}&apos; is selected: select the geotags of the partition to fly, or clear SELECTED_ONLY.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="126"/>
        <source>GEOTAGS: layer &apos;{}&apos; has no features: there is nothing to fly over.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="164"/>
        <source>With this camera at {alt:g} m and {v:g} m/s, one photo every {s:.2f} s gives {o:g} % forward overlap.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="226"/>
        <source>{fmt}: {files}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="233"/>
        <source>{g} geotag(s) → {w} waypoint(s) in {m} mission(s); route {km:.2f} km; estimated flight time {t:.1f} min at {v:g} m/s and {alt:g} m.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="239"/>
        <source>  mission {n}: {w} waypoint(s), {l:.0f} m, {t:.1f} min</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ScreenCheckpoints</name>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="45"/>
        <source>ONNX checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="47"/>
        <source>Validation flights (frame layers with their images)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="49"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="51"/>
        <source>Detection threshold (empty: each checkpoint&apos;s default)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="55"/>
        <source>Pixel F1: match radius (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="58"/>
        <source>Collapsed if the distinct-position fraction is below</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="61"/>
        <source>Too sparse if detections per frame on the worst flight are below</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="64"/>
        <source>Checkpoint table (CSV)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="66"/>
        <source>Checkpoint table (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="68"/>
        <source>Frontier plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="70"/>
        <source>Healthy checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="76"/>
        <source>CHECKPOINTS: give at least one ONNX file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="78"/>
        <source>FRAMES: give at least one validation flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="88"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="173"/>
        <source>Cancelled by the user.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SealPreregistration</name>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="42"/>
        <source>ONNX checkpoints (one arm each)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="44"/>
        <source>Detection threshold of the arms</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="48"/>
        <source>Descriptive configurations (optional: a sweep or screen JSON, recorded only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="51"/>
        <source>Note (what was chosen on which flights, what will be scored)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="54"/>
        <source>Sealed rule (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="56"/>
        <source>Seal (SHA-256)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="61"/>
        <source>CHECKPOINTS: give at least one ONNX file.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SensorBoundAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="34"/>
        <source>Grid stride [px] (1 = every pixel)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="37"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="39"/>
        <source>Report with plots (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="42"/>
        <source>λ_max field, one band per altitude (GeoTIFF in pixel coordinates)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="93"/>
        <source>{name}: the stride {stride} px does not divide the frame size, so the raster stops at the last multiple of the stride; the JSON suprema still include the frame edges.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="102"/>
        <source>{name}: cannot create the GeoTIFF {path}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SimulateCampaign</name>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="62"/>
        <source>Pose noise Σ0: x, y, z (m), roll, pitch, yaw (deg)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="65"/>
        <source>Noise off (ideal poses, altimeter and geotags)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="67"/>
        <source>Render frames (off: poses and geotags only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="69"/>
        <source>Terrain</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="76"/>
        <source>Geoid undulation N for altMSL (m; empty: EGM96 at the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="80"/>
        <source>Output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="84"/>
        <source>Terrain model (truth/dem.tif, ellipsoidal heights; none for flat terrain)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="86"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SweepOperatingPoints</name>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="67"/>
        <source>Detection layers (one per flight, detected at the lowest threshold)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="70"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="72"/>
        <source>Frame layers (one per flight, same order)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="76"/>
        <source>De-duplication grid cell (cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="79"/>
        <source>Edge buffer of the in-view test (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="82"/>
        <source>Credible: mean geotags per hit cluster at most</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="85"/>
        <source>Credible: mean median cluster extent at most (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="88"/>
        <source>Configurations (CSV)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="90"/>
        <source>Configurations and Pareto front (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="93"/>
        <source>Frontier plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="114"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>TerrainSlopeAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="38"/>
        <source>Altitude above the ground [m]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="42"/>
        <source>Steepest slope studied [degrees]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="45"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="47"/>
        <source>Contour plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="55"/>
        <source>{name}: the altitude must be greater than 0 m, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="60"/>
        <source>{name}: the steepest slope must lie between 0° and 90° (exclusive), got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="76"/>
        <source>{where}: {d:.2f} m from the nadir point at {alt:g} m (ρ = {rho:.3f}) — labels stay within {tol:g} px up to a {limit:.1f}° uphill slope.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="100"/>
        <source>Farthest left/right edge midpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="101"/>
        <source>Farthest top/bottom edge midpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="102"/>
        <source>Farthest frame corner</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>WriteLabels</name>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="47"/>
        <source>Geotags (surveyed targets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="49"/>
        <source>Frames (from Import flight log or Import DJI images)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="52"/>
        <source>Soft-label σ (px); empty: the sensor-bound dock's value, else 10</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="55"/>
        <source>…or σ from a sensorbound result (JSON): r / 3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="58"/>
        <source>Edge buffer (px): geotags this close to the border are &apos;edge&apos;, not labels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="62"/>
        <source>Write one soft-label raster per frame</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="64"/>
        <source>Write a tiled training set (image and label tiles)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="66"/>
        <source>Tile size (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="69"/>
        <source>Negative tiles kept per positive tile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="72"/>
        <source>Random seed for the negative-tile sample</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="75"/>
        <source>Write COCO-keypoints JSON</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="77"/>
        <source>Label folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="78"/>
        <source>Frames with label counts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="81"/>
        <source>Geotags with frames seen</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="107"/>
        <source>GEOTAGS and FRAMES are both required.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>alg</name>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="50"/>
        <source>De-duplication grid cell (cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="53"/>
        <source>DBSCAN radius EPS (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="56"/>
        <source>DBSCAN minimum points per neighbourhood (itself included)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="64"/>
        <source>Match radius geotag ↔ cluster core points EPS_PRED (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="67"/>
        <source>Edge buffer of the in-view test (px)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
