<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1">
<context>
    <name>@default</name>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="117"/>
        <source>The BirdsEye Processing provider could not be registered.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="126"/>
        <source>&amp;BirdsEye</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="128"/>
        <source>BirdsEye</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="131"/>
        <source>BirdsEye algorithms…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="133"/>
        <source>Open the Processing toolbox showing the BirdsEye algorithms</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="204"/>
        <source>The Processing plugin is not active: enable it under Plugins ▸ Manage and Install Plugins, then try again.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="255"/>
        <source>The &apos;{title}&apos; panel could not be opened ({module}.{cls}: {error}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="67"/>
        <source>Review clusters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="199"/>
        <source>Review setup</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="203"/>
        <source>choose one or more detection layers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="204"/>
        <source>Outputs of Detect targets over one flight (several checkpoints or thresholds are reviewed together: one verdict per spot).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="206"/>
        <source>Detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="212"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="216"/>
        <source>The survey points (Import geotags).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="217"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="222"/>
        <source>GeoPackage holding the append-only verdict log (table birdseye_verdicts). Default: the first detection layer&apos;s GeoPackage, else one next to the project.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="225"/>
        <source>Verdict log</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="227"/>
        <source>Recorded with every verdict.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="229"/>
        <source>Reviewer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="231"/>
        <source>Clustering and matching</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="251"/>
        <source>DBSCAN minimum points per neighbourhood (itself included).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="262"/>
        <source>Size of the image window cut around a detection.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="269"/>
        <source>Map scale the canvas zooms to around each unit.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>Grid cell</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>EPS</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>Min. points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>EPS_PRED</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>Edge buffer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>Chip window</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>Map scale</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="277"/>
        <source>Start / resume review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="291"/>
        <source>No review started</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="301"/>
        <source>All layers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="311"/>
        <source>Fired by</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="313"/>
        <source>Show</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="351"/>
        <source>Previous (P)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="353"/>
        <source>Next (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="370"/>
        <source>Undo (Ctrl+Z)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="372"/>
        <source>Add missed target (A)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="378"/>
        <source>Propagate to units within {:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="379"/>
        <source>Off by default. When on, a verdict also votes (provenance propagated:{rule}) on the units chained to this one by gaps of at most {eps:.2f} m; conflicting votes are resolved under the three conventions, all shown.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="384"/>
        <source>Next unit after a verdict</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="391"/>
        <source>&lt;b&gt;Scores per detection layer&lt;/b&gt; — after review under each tie-break convention</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="393"/>
        <source>Recall and the geotag-matched cluster fraction (GMCF), computed as Evaluate detections computes them from this verdict log.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="397"/>
        <source>before
review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="401"/>
        <source>After review, {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="415"/>
        <source>GMCF is a lower bound on precision, not precision; recall after review is an upper bound (≥). The spread between the conventions is part of the result.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="172"/>
        <source>Choose at least one detection layer (an output of Detect targets).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="178"/>
        <source>Choose a GeoPackage for the verdict log (save the project first to get one next to it).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="238"/>
        <source>{n} units from {k} layer(s); verdict log {path}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="308"/>
        <source>A layer of the review was removed from the project; the review stopped. Every verdict is in the log; choose the layers again to resume.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="76"/>
        <source>Added target</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="345"/>
        <source>&lt;b&gt;{pos}&lt;/b&gt; of {vis} shown · {done} of {n} units reviewed · {added} added</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="398"/>
        <source>An added target can only be withdrawn (0 or Backspace) or undone.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="409"/>
        <source>Saved: {key} → {verdict}{more} ({time} UTC)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="409"/>
        <source>, {} propagated vote(s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="424"/>
        <source>Nothing to undo.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="428"/>
        <source>Undone: action {action} on {key} (rows appended; nothing deleted).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="446"/>
        <source>The verdict was NOT saved: {error}. Check that {path} is writable and not locked, then try again.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="461"/>
        <source>Click the map where the missed target is (Esc or right click cancels).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="482"/>
        <source>Added target {key} (Ctrl+Z undoes it).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="482"/>
        <source>A target is already recorded there.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="503"/>
        <source>No units: the detection layers have no clusters at these settings.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="504"/>
        <source>Nothing to show</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="516"/>
        <source>Loading frames…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="523"/>
        <source>&lt;b&gt;Added target&lt;/b&gt; {key}&lt;br&gt;{lat:.7f}°, {lon:.7f}° · recorded as a target the detector missed (the &lt;i&gt;a&lt;/i&gt; term). 0 withdraws it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="137"/>
        <source>geotag {ids} within {eps:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="137"/>
        <source>no geotag within {eps:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="144"/>
        <source>none yet</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="145"/>
        <source>the conventions disagree</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="430"/>
        <source>The frames could not be read: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="432"/>
        <source>No frame of the frame layer shows this spot.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="438"/>
        <source>frame {f}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="444"/>
        <source>{shown} of {n} frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="580"/>
        <source>updating…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="589"/>
        <source>Scores could not be computed: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="113"/>
        <source>recall</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="115"/>
        <source>GMCF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="236"/>
        <source>Review verdicts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="454"/>
        <source>Cannot start the review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="454"/>
        <source>Inputs changed since verdicts were recorded</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="113"/>
        <source>Accept</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="113"/>
        <source>Reject</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="113"/>
        <source>: κ* = λ_target / sup; every variance of the budget may grow by this factor. Accept when κ* ≥ 1.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="136"/>
        <source>Sensor-bound calculator</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="173"/>
        <source>Camera</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="180"/>
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
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="248"/>
        <source>Label tolerance and altitudes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="253"/>
        <source>Label radius r at 3σ: the label must stay within r px of the target.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="257"/>
        <source>σ_label = r/3: the Gaussian sigma of the soft labels (λ_target = σ_label²).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="261"/>
        <source>Tolerance r (3σ)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="263"/>
        <source>e.g. 10, 20</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="264"/>
        <source>Heights above the ground in metres, separated by commas.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="266"/>
        <source>Altitudes [m]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="270"/>
        <source>Verdicts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="278"/>
        <source>Altitude</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="278"/>
        <source>sup tr Σ
[px²]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="278"/>
        <source>sup λmax
[px²]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="278"/>
        <source>κ* trace</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="278"/>
        <source>κ* exact</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="280"/>
        <source>Largest trace of the label covariance over the frame (the linear, pessimistic criterion).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="282"/>
        <source>Largest eigenvalue of the label covariance over the frame (the exact criterion).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="288"/>
        <source>Details for</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="290"/>
        <source>The altitude whose budget table and λ_max field are shown.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="298"/>
        <source>Your σ</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="298"/>
        <source>Balanced σ
(trace)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="298"/>
        <source>Balanced σ
(exact)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="298"/>
        <source>Share of
error</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="300"/>
        <source>The largest budget with no axis starved (maximum Σ log σ²) that meets the exact bound.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="302"/>
        <source>Each axis&apos;s share of the error of your budget at the worst pixel: improve the largest first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="327"/>
        <source>λ_max field — red: the tolerance λ_target</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="340"/>
        <source>Evaluate every pixel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="341"/>
        <source>Re-evaluate on the full-resolution grid (stride 1 px), as the Processing algorithm does by default.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="344"/>
        <source>Use σ_label in Write labels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="345"/>
        <source>Store σ_label = r/3 px in the project; Write labels uses it as its default label sigma (SIGMA_PX).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="348"/>
        <source>Run in Processing…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="349"/>
        <source>Open the Sensor bound algorithm with these values, to write the JSON results, the HTML report and the λ_max raster.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="374"/>
        <source>Altitudes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="454"/>
        <source>σ_label = {value:.2f} px</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="481"/>
        <source>every pixel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="481"/>
        <source>preview grid: every {s} px and the frame edges</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="486"/>
        <source>λ_target = (r/3)² = {lam:.4g} px² · {grid}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="505"/>
        <source>worst pixel ({u:.0f}, {v:.0f})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="523"/>
        <source>worst at ({u:.0f}, {v:.0f})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="553"/>
        <source>σ_label = {s:.2f} px stored in the project: Write labels will use it as its label sigma (project variable @birdseye_sigma_label_px).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/map_context.py" line="81"/>
        <source>Verdict layer {uri} could not be loaded</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="36"/>
        <source>Sealed rule verified (seal {value}…, sealed {sealed_at}); arm '{name}': its operating point replaces the dialog's values: {value2}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="50"/>
        <source>{path}: not a sensorbound result (expected inputs.tolerance_px): {exc}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="55"/>
        <source>{path}: the pose-noise budget is rejected at {items}; labels of σ = {value:g} px would not contain the projection error there</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="232"/>
        <source>{n_labels} labels in {n_frames_with_labels} of {n_frames} frames (labels per labelled frame: mean {mean:g}, max {max}); {n_geotags_in_view} of {n_geotags} geotags in view (frames per geotag: mean {mean2:g}, max {max2})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="251"/>
        <source>{n_occluded} projections were hidden behind terrain (not written)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="254"/>
        <source>{n_edge} projections fell within the edge buffer (not written)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="259"/>
        <source>{n_never} geotag(s) never in view of any frame: {shown}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="263"/>
        <source>{value} image(s) could not be read for tiles; first: {value2}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="146"/>
        <source>DEM {source}: {value}×{value2} cells of {cell_size_m:g} m, heights {value3:.1f}…{value4:.1f} m ({vertical_datum})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="68"/>
        <source>{always}; for some inputs: {sometimes}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="70"/>
        <source>for some inputs: {sometimes}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="71"/>
        <source>no algorithm (developer tools only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="78"/>
        <source>missing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="80"/>
        <source>update from {version}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="82"/>
        <source>installed by BirdsEye ({version})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="86"/>
        <source>installed ({version})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="133"/>
        <source>BirdsEye — Python packages</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="152"/>
        <source>Package</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="152"/>
        <source>State</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="152"/>
        <source>Needed by</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="170"/>
        <source>Install</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="174"/>
        <source>Show pip&apos;s log</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="309"/>
        <source>Close</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="224"/>
        <source>Every Python package BirdsEye&apos;s algorithms need is installed in the Python QGIS runs.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="273"/>
        <source>Installing {names}…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="277"/>
        <source>Cancel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="294"/>
        <source>Installed: {names}. The algorithms can use them now; no restart needed.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="294"/>
        <source>nothing new</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="299"/>
        <source>The installation failed: {message}
pip&apos;s log is below; the packages already there are unchanged.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="305"/>
        <source>Cancelled; nothing was installed.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="317"/>
        <source>Cancelling…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="53"/>
        <source>Review clusters: walk through the detected clusters beside the survey, judge each, and see recall and GMCF before and after review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="56"/>
        <source>Sensor-bound calculator: which pose-noise budget keeps labels within their pixel tolerance for a camera and flying height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="226"/>
        <source>Install dependencies…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="155"/>
        <source>Install the Python packages BirdsEye&apos;s algorithms need</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="224"/>
        <source>Some algorithms need Python packages that are not installed: {names}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="235"/>
        <source>Consensus clusters (one per spot, all layers)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="236"/>
        <source>The method&apos;s (per frame, complete linkage at {px:.0f} px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="238"/>
        <source>How detections become review units. Consensus clusters (the default) pool the layers and judge each spot once. The method&apos;s: detections within EPS_PRED of an in-view geotag are set aside one by one; per frame, the rest are grouped so that every two detections of a group are at most {px:.0f} px apart; each group is a unit, so a spot is judged once per frame.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>Review units</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="237"/>
        <source>How roll, pitch and yaw turn the camera. As the method: about the camera&apos;s x, y and optical axes; nadir, image top towards the nose: roll and pitch trade places.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="241"/>
        <source>Mount</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="92"/>
        <source>{GROUND_MODEL}: the method&apos;s plane stands in for the level ground; with a terrain model ({DEM}) the terrain is the ground. Give one or the other.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="76"/>
        <source>no release for Python {version}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="84"/>
        <source>installed ({version}; untested outside {versions})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="152"/>
        <source>Versions</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="216"/>
        <source>BirdsEye&apos;s algorithms need {count} Python package(s) that the Python QGIS runs does not have. Tick the ones to install and press Install: pip installs them, at versions that suit this Python and the packages QGIS already has, with what they depend on, into a folder of your QGIS profile:
{folder}
QGIS&apos;s own packages are not changed. pip downloads them from the Python Package Index (or the index your pip is set up to use).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="210"/>
        <source>The flight&apos;s frame layer (Import flight log, Import drone images or Import camera solution): poses, camera and image of every frame.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="242"/>
        <source>Of these, review targets: {n_in_view} of {n_targets} in view, {n_labels} labels.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="247"/>
        <source>Hard negatives: {n_in_view} of {n_clusters} in view, in {n_frames} frame(s); {n_tiles} hard-negative tile(s) written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="234"/>
        <source>Optional — {title} for Train detector ({build} build{why}): {state}. It is installed into its own folder, {folder}, and runs in a separate training process: QGIS itself never loads it. Several hundred MB (the CUDA build: gigabytes).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="234"/>
        <source>, an NVIDIA driver is present</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="241"/>
        <source>Install {title}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="212"/>
        <source>The detections were placed on {ground}, which cannot be used here ({reason}). Chips and geotags in view stand on the level plane instead: positions in the chips and the scores may differ from those of Evaluate detections given that DEM.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="217"/>
        <source>The review stands on the level plane, not on the detections&apos; DEM</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/layers.py" line="419"/>
        <source>the camera model of frame {frame} was cut at {length} characters: {format} keeps at most {length} characters in a text field and a camera model needs about 500: the layer was probably saved to it after the import (Save Features As…). Save the original frame layer as a GeoPackage (.gpkg) instead, or run the import again with its output written to a GeoPackage (or to this format: the import then splits the camera over fields camera, camera_2, …).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/layers.py" line="419"/>
        <source>the layer&apos;s file format (e.g. ESRI Shapefile)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/layers.py" line="464"/>
        <source>The output&apos;s format keeps at most {n} characters in a text field: each frame&apos;s camera model goes on in fields {fields}; keep them with the layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="272"/>
        <source>Training: {stage}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="274"/>
        <source>Training process {pid} started: torch {torch} on {device} ({threads} threads), backbone {backbone}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="279"/>
        <source>{stage} step {step}: loss {loss:.4f}, validation {val} ({seconds:.0f} s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="283"/>
        <source>Checkpoint written: {path} ({stage}, step {step})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="136"/>
        <source>{layer}: its detections were placed on {recorded}; {DEM} is {given}. Check that both hold the same terrain in the same vertical reference.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="120"/>
        <source>DEM against the frames: {check}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>BirdsEyeAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/base.py" line="104"/>
        <source>Cancelled by the user.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="16"/>
        <source>1 · Field data</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="17"/>
        <source>2 · Flight planning</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="18"/>
        <source>3 · Training labels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="19"/>
        <source>4 · Detection and review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="20"/>
        <source>5 · Platform design</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="21"/>
        <source>6 · Simulation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="112"/>
        <source>This algorithm needs the Python package(s) {names}, which the Python QGIS runs does not have. In QGIS, choose BirdsEye › Install dependencies… to install them; or install them yourself: python -m pip install {pins}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="119"/>
        <source>This algorithm needs the Python package(s) {names}, which have no release for the Python QGIS runs (Python {version}); it runs in a QGIS with a newer Python.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ClusterDetections</name>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="51"/>
        <source>Detections (from Detect targets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="54"/>
        <source>Geotags (optional: fills matched_geotag_ids and hit)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="57"/>
        <source>Frames of the flight (optional: only in-view geotags can match)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="62"/>
        <source>Clusters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="64"/>
        <source>De-duplicated points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="74"/>
        <source>DETECTIONS: the detection layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="86"/>
        <source>The detection layer holds no detection with a position.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="151"/>
        <source>OUTPUT: the cluster layer cannot be created.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="174"/>
        <source>OUTPUT_POINTS: the point layer cannot be created.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="77"/>
        <source>{dropped} detection(s) without a position or score were left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="115"/>
        <source>No FRAMES given: every geotag is treated as in view.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="122"/>
        <source>{n_hit_clusters} of {n} clusters match an in-view geotag; {n_recovered} of {n_in_view} in-view geotags recovered.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="134"/>
        <source>{n_det} detections → {n_points} de-duplicated points → {n} clusters ({NOISE_POINTS} points are noise).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="42"/>
        <source>Cluster detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="110"/>
        <source>{n} frame(s) without a ground height (flag no_ground_height; first: {items}) were not counted as processed: the geotags only they see are not in view.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ClusteringParametersMixin</name>
    <message>
        <location filename="../processing/parameters/clustering.py" line="25"/>
        <source>De-duplication grid cell (cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="28"/>
        <source>DBSCAN radius EPS (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="31"/>
        <source>DBSCAN minimum points per neighbourhood (itself included)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="40"/>
        <source>Match radius geotag ↔ cluster core points EPS_PRED (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="44"/>
        <source>Edge buffer of the in-view test (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="69"/>
        <source>{name}: give at least one detection layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="72"/>
        <source>{name}: give one frame layer per detection layer, in the same order (got {detections} detection layer(s) and {frames} frame layer(s)).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="80"/>
        <source>{layer}: {n} detection(s) without a position or score left out</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>CompareDetectors</name>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="37"/>
        <source>Compare detectors</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="49"/>
        <source>Detections of the old detector (before)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="51"/>
        <source>Detections of the new detector (after), same flight</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="54"/>
        <source>Frames of the flight (both detectors ran on them)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="56"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="60"/>
        <source>Review verdicts (optional: adds the POST scores of both)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="63"/>
        <source>What changed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="65"/>
        <source>Comparison (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="67"/>
        <source>Report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="81"/>
        <source>{name}: the layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="86"/>
        <source>{name}: {n} detection(s) without a position or score left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="91"/>
        <source>Both layers come from the same model file (model_digest) at the same threshold: the comparison shows no change of detector.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="102"/>
        <source>GEOTAGS: the layer holds no point with a position.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="130"/>
        <source>OUTPUT: the change layer cannot be created.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="158"/>
        <source>{name}: cannot write {path} ({exc})</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>DemParametersMixin</name>
    <message>
        <location filename="../processing/parameters/dem.py" line="61"/>
        <source>Terrain model (DEM/DSM raster, projected CRS in metres; empty: level ground)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="64"/>
        <source>DEM heights are measured from</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="72"/>
        <source>Ground model without a DEM</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="67"/>
        <source>Geoid undulation N at the site (m; ellipsoidal = MSL + N; empty: EGM96 from PROJ&apos;s grid where one is needed)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>DesignParametersMixin</name>
    <message>
        <location filename="../processing/parameters/design.py" line="57"/>
        <source>Camera calibration (Kalibr or OpenCV YAML; overrides the intrinsics below)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="73"/>
        <source>Pose sigmas, 1σ (x, y, z in metres; roll, pitch, yaw in degrees)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="81"/>
        <source>Altitudes above the ground [m], comma-separated</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="86"/>
        <source>Label tolerance r [px] (label radius at 3σ)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="113"/>
        <source>Camera from {file}: {w}×{h} px, fx {fx:.4f}, fy {fy:.4f}, cx {cx:.4f}, cy {cy:.4f} px (the typed intrinsics are ignored).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="131"/>
        <source>{name}: the focal length must be greater than 0 px, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="161"/>
        <source>{name}: the label tolerance must be greater than 0 px, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="168"/>
        <source>Cancelled by the user.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="54"/>
        <source>Custom</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="99"/>
        <source>Platform {name}. Sources: {sources}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="110"/>
        <source>{CALIBRATION}: {exc}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="122"/>
        <source>Camera of the platform: {w}×{h} px, fx {fx:.4f}, fy {fy:.4f}, cx {cx:.4f}, cy {cy:.4f} px (the typed intrinsics are ignored).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="54"/>
        <source>Platform preset (camera, pose sigmas and mount; Custom: the values below)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="76"/>
        <source>Camera mount (how roll, pitch and yaw turn the camera)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="102"/>
        <source>Pose sigmas of the platform: {sigmas} ({hint}; the typed SIGMAS are ignored), camera mount: {mount} (the chosen {MOUNT} is ignored).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Detect</name>
    <message>
        <location filename="../processing/algorithms/detect.py" line="45"/>
        <source>ONNX heatmap model (empty: the bundled demo model)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="48"/>
        <source>Probability threshold (empty: the model&apos;s default)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="51"/>
        <source>Edge buffer (px): detections closer to the image border are dropped</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="55"/>
        <source>Detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="57"/>
        <source>Heatmap folder (one PNG per frame)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="63"/>
        <source>SHA-256 of the model</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="85"/>
        <source>Model {name} (sha256 {value}…): {resolution_cm:g} cm/px, tiles {tile_size} px with {overlap_px} px overlap, threshold {used:g}{value2}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="108"/>
        <source>{detections} detections in {processed} frames ({value:.2f} per frame); {edge} dropped within {edge_buffer_px:g} px of the border, {no_ground} whose ray missed the ground; {skipped} frames skipped.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="139"/>
        <source>Frame {frame_id}: {skipped}; skipped.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="158"/>
        <source>{n_coarse} frame(s) (e.g. {items}) are coarser than 1.5× the model's resolution of {resolution_cm:g} cm/px: targets look smaller than in training, so expect fewer detections (fly lower or use a model trained at that resolution).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="31"/>
        <source>Detect targets (ONNX heatmap model)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="42"/>
        <source>Frames (from Import flight log, Import drone images or Import camera solution)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="99"/>
        <source>{FRAMES} has no CRS: the detections are written in {crs}, the UTM zone of the site.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>EvaluateDetections</name>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="58"/>
        <source>Detection layers (one per flight)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="60"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="62"/>
        <source>Frame layers (one per flight, same order)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="66"/>
        <source>Review verdicts (optional: adds the POST scores)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="69"/>
        <source>Sealed selection rule (optional: verified, its operating point is used)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="75"/>
        <source>Scores (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="77"/>
        <source>Report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="91"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="94"/>
        <source>GEOTAGS: the layer holds no point with a position.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="117"/>
        <source>{name}: {n_frames_without_ground} frame(s) without a ground height were not counted as processed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="124"/>
        <source>OUTPUT_JSON: cannot write {out_json} ({exc})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="132"/>
        <source>OUTPUT_REPORT: cannot write {out_report} ({exc})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="46"/>
        <source>Evaluate detections (recall, GMCF)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="72"/>
        <source>Arm to score (its name in the sealed rule; needed when arms share the checkpoint)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="101"/>
        <source>ARM: names an arm of a sealed selection rule; give the rule (PREREGISTRATION) too, or leave ARM empty.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportCameras</name>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="36"/>
        <source>Align to the images&apos; GPS tags (needs IMAGES)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="36"/>
        <source>Already georegistered in ECEF (model_aligner --alignment_type ecef)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="36"/>
        <source>East-north-up at the origin given in ENU_ORIGIN</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="69"/>
        <source>Folder of the images (optional; matched by file name)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="72"/>
        <source>Ground height for frames without tie points (m, same reference as the solution; optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="76"/>
        <source>A COLMAP model&apos;s frame</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="79"/>
        <source>ENU origin of a COLMAP model: lat, lon, ellipsoidal height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="84"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="87"/>
        <source>Solved frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="95"/>
        <source>Frames written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="96"/>
        <source>Cameras the solution did not align</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="120"/>
        <source>Camera: {width}×{height} px, fx {fx:.2f}, fy {fy:.2f}, cx {cx:.2f}, cy {cy:.2f} ({source})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="124"/>
        <source>Output CRS: {value}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="45"/>
        <source>Import camera solution (Metashape, OpenDroneMap, COLMAP, Pix4D)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="64"/>
        <source>Camera solution (Metashape cameras .xml, OpenSfM/ODM reconstruction.json, a COLMAP model folder, or Pix4D&apos;s calibrated_camera_parameters.txt)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="81"/>
        <source>CRS of a Pix4D project&apos;s coordinates (its output CRS: projected, metres)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="89"/>
        <source>Control points (surveyed markers, a geotag layer)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="92"/>
        <source>Label check: each pinned image mark and its label&apos;s distance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="98"/>
        <source>Median distance of the control points&apos; labels from their marks (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="100"/>
        <source>90th percentile of that distance (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="137"/>
        <source>SOLUTION_CRS: {crs} is not a projected CRS in metres; give the Pix4D project&apos;s output CRS (easting, northing and height in metres)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="152"/>
        <source>Control points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="166"/>
        <source>Label check (pinned marks)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportDjiImages</name>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="37"/>
        <source>Camera calibration (optional; Kalibr or OpenCV YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="40"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="48"/>
        <source>Frames written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="49"/>
        <source>Images that cannot be placed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="65"/>
        <source>Not placed: {error}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="68"/>
        <source>Camera: {width}×{height} px, fx {fx:.1f}, fy {fy:.1f} ({source})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="72"/>
        <source>Output CRS: {value}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="24"/>
        <source>Import drone images</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="35"/>
        <source>Folder of drone images (JPEG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="42"/>
        <source>Flight height above the take-off ground (m; for images without a relative altitude)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="46"/>
        <source>Drone frames</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportFlightLog</name>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="40"/>
        <source>Pose log (BirdsEye CSV or flight_data.db)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="43"/>
        <source>Image folder (images.csv or &lt;sec&gt;.&lt;nsec&gt;.png|jpg files)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="46"/>
        <source>Camera calibration (Kalibr camchain or OpenCV YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="49"/>
        <source>Camera frame rate (frames/s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="52"/>
        <source>Minimum altimeter SNR (dB)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="54"/>
        <source>RTK filter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="56"/>
        <source>UTM zone of flight_data.db x, y (only for flight_data.db)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="58"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="61"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="63"/>
        <source>Flight line</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="78"/>
        <source>Camera: {width}×{height} px, fx {fx:.1f}, fy {fy:.1f} ({source})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="95"/>
        <source>Output CRS: {value}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="24"/>
        <source>Import flight log</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportGeotags</name>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="66"/>
        <source>Geotag file (rover CSV, CSV with header, NMEA)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="69"/>
        <source>…or a point layer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="71"/>
        <source>File format</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="82"/>
        <source>Fix filter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="87"/>
        <source>Antenna pole height (m), subtracted from heights</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="90"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="92"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="104"/>
        <source>Give either a geotag file (INPUT) or a point layer (INPUT_LAYER), not both and not neither.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="122"/>
        <source>The input holds no usable geotag.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="155"/>
        <source>No geotag is left to write (all were filtered out).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="125"/>
        <source>{n_problems} bad row(s) left out; first: {examples}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="140"/>
        <source>{dropped_not_fixed} geotag(s) without an RTK fixed solution were left out (fix filter: RTK fixed only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="152"/>
        <source>{duplicates} geotag(s) lie within 2 cm of an earlier one (flag duplicate_2cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="157"/>
        <source>Output CRS: {value}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="35"/>
        <source>Import geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="52"/>
        <source>From the file (a unit in the column&apos;s name, the coordinate-system name, a units column; else metres)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="52"/>
        <source>Metres</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="52"/>
        <source>International feet (0.3048 m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="52"/>
        <source>US survey feet (1200/3937 m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="75"/>
        <source>Unit of heights and accuracies</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="78"/>
        <source>Geoid undulation N for a file with only MSL heights (m; ellipsoidal = MSL + N; empty: EGM96 from PROJ&apos;s grid)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="84"/>
        <source>Keep geotags with a horizontal accuracy within (m; empty: all)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="119"/>
        <source>Reading: {note}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="132"/>
        <source>Fix quality of the input: {counts}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="136"/>
        <source>Horizontal accuracy of the input: median {median:.3f} m, worst {worst:.3f} m ({n_known} of {n_tags} geotags give one)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="144"/>
        <source>{dropped} geotag(s) with a horizontal accuracy worse than {limit:g} m were left out (MAX_H_ACCURACY_M)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="148"/>
        <source>{unknown} geotag(s) have no horizontal accuracy in the input and were kept (MAX_H_ACCURACY_M cannot judge them)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>MonteCarloBoundAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="49"/>
        <source>Monte Carlo samples</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="51"/>
        <source>Random seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="52"/>
        <source>Scaling study: smallest variance factor</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="54"/>
        <source>Scaling study: largest variance factor</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="56"/>
        <source>Scaling study: number of factors (log-spaced)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="58"/>
        <source>Scaling study per axis as well (7× the work)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="60"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="62"/>
        <source>Scaling-study plot (PNG, one panel per altitude)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="97"/>
        <source>{alt:g} m: max sKLD at the deployed budget {skld:.3g} nats over {n} test pixels (threshold {thr:g}) → the linearised bound {verdict}; exact κ* = {kappa:.3g}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="97"/>
        <source>holds</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="97"/>
        <source>does NOT hold</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="120"/>
        <source>{name}: the smallest variance factor must be greater than 0, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="123"/>
        <source>{name}: the largest variance factor must exceed {other} ({low:g}), got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="31"/>
        <source>Sensor bound: Monte Carlo check</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>PlanFlight</name>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="99"/>
        <source>Geotags (point layer)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="101"/>
        <source>Selected geotags only</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="106"/>
        <source>Home: take-off and landing point (optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="113"/>
        <source>Camera calibration (Kalibr or OpenCV YAML; optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="119"/>
        <source>Capture</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="129"/>
        <source>Plan even if the points spread over more than 10 km</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="137"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="141"/>
        <source>Waypoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="143"/>
        <source>Route</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="153"/>
        <source>Mission files written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="175"/>
        <source>GEOTAGS: the geotag layer could not be opened.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="178"/>
        <source>SELECTED_ONLY is set but no geotag of layer &apos;{}&apos; is selected: select the geotags of the partition to fly, or clear SELECTED_ONLY.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="189"/>
        <source>GEOTAGS: layer &apos;{}&apos; has no features: there is nothing to fly over.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="244"/>
        <source>With this camera at {alt:g} m and {v:g} m/s, one photo every {s:.2f} s gives {o:g} % forward overlap.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="306"/>
        <source>{fmt}: {files}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="316"/>
        <source>{g} geotag(s) → {w} waypoint(s) in {m} mission(s); route {km:.2f} km; estimated flight time {t:.1f} min at {v:g} m/s and {alt:g} m.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="322"/>
        <source>  mission {n}: {w} waypoint(s), {l:.0f} m, {t:.1f} min</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="65"/>
        <source>Plan the survey flight</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="134"/>
        <source>With REVIEW: fly only to the unresolved clusters (the geotags then only tell which clusters they match)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="199"/>
        <source>UNRESOLVED_ONLY needs a review: give REVIEW and the detection layers it judged (REVIEW_DETECTIONS).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="202"/>
        <source>The review left no cluster unresolved (uncertain, unreviewed or with conflicting verdicts): there is nothing to fly back to.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="314"/>
        <source>{u} unresolved cluster(s) of the review are targets too (waypoint field provenance: review).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="103"/>
        <source>Geotag id field (empty: &apos;id&apos; if present, else the row number)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="185"/>
        <source>{problem}: remove the feature or give it a position, so no target is left out of the flight.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ProcessOdm</name>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="23"/>
        <source>Process on an OpenDroneMap node</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="35"/>
        <source>Folder of the flight&apos;s images</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="37"/>
        <source>NodeODM / ClusterODM address</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="39"/>
        <source>Access token (if the node asks for one)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="41"/>
        <source>OpenDroneMap options (name=value, separated by commas)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="44"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="46"/>
        <source>Folder for the downloaded reconstruction</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="48"/>
        <source>Solved frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="50"/>
        <source>Frames written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="61"/>
        <source>Reconstruction: {path}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>RefinePoses</name>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="37"/>
        <source>Refine frame poses (structure from motion)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="52"/>
        <source>Image size for feature extraction (px, longer side)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="55"/>
        <source>Features per image (at most)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="58"/>
        <source>Refine focal length and distortion (only with relief, oblique views or ground control)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="66"/>
        <source>Refined frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="68"/>
        <source>Report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="70"/>
        <source>Frames registered</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="75"/>
        <source>FRAMES is required.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="82"/>
        <source>{n} frames; SIFT features at {size} px, at most {features} per image</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="108"/>
        <source>Registered {n} of {total} frames in {seconds:.0f} s ({rate:.1f} images per minute); intrinsics {intrinsics}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="113"/>
        <source>Aligned to the GNSS positions: residual RMS {rms:.3f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="122"/>
        <source>{n} frame(s) keep their metadata pose (flag not_refined); first: {items}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="140"/>
        <source>OUTPUT_REPORT: cannot write {path} ({error})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="49"/>
        <source>Frames (from Import drone images, Import flight log or Import camera solution)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="116"/>
        <source>Camera-to-ground distance of the block / (GNSS height − ground height): {ratio:.4f}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="61"/>
        <source>Geotags with surveyed heights (optional: the ground for a nominal camera&apos;s focal length where frames have an RTK fix or no ground; else compared with theirs)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="88"/>
        <source>{n} geotags with a surveyed height: the ground plane at {h:.2f} m (ellipsoidal)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="98"/>
        <source>DEM against the frames: {check}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="104"/>
        <source>Ground of the GNSS camera-to-ground distances: {text}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="107"/>
        <source>Warning: {text}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ReviewParametersMixin</name>
    <message>
        <location filename="../processing/parameters/review.py" line="32"/>
        <source>Review verdicts (the review dock&apos;s birdseye_verdicts table; optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="35"/>
        <source>Detection layers the review judged (with REVIEW)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="39"/>
        <source>Frame layers of those detections (one per layer, same order)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="58"/>
        <source>REVIEW_DETECTIONS is given without REVIEW: give the review&apos;s verdict table too, or leave REVIEW_DETECTIONS empty.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="63"/>
        <source>REVIEW: give the detection layer(s) the review judged (REVIEW_DETECTIONS): the verdicts name spots, the clusters come from those detections.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="79"/>
        <source>{layer}: {n} detection(s) without a position or score left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="89"/>
        <source>Review ({review}): {n} cluster(s) in {layers} detection layer(s); {hit} match a geotag; of the others {confirmed} confirmed real, {hard} hard negative, {conflicting} with conflicting verdicts, {uncertain} uncertain, {unreviewed} unreviewed.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="105"/>
        <source>{layer}: its detections were placed on {recorded}; the review&apos;s in-view test stands on the level plane here (this algorithm has no DEM, or none was given).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ScreenCheckpoints</name>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="80"/>
        <source>ONNX checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="82"/>
        <source>Validation flights (frame layers with their images)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="84"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="97"/>
        <source>Pixel F1: match radius (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="100"/>
        <source>Collapsed if the distinct-position fraction is below</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="106"/>
        <source>Checkpoint table (CSV)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="108"/>
        <source>Checkpoint table (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="110"/>
        <source>Frontier plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="112"/>
        <source>Healthy checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="118"/>
        <source>CHECKPOINTS: give at least one ONNX file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="120"/>
        <source>FRAMES: give at least one validation flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="129"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="161"/>
        <source>{name} on {flight_name}: {skipped} frame(s) skipped (unreadable image or no ground height)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="61"/>
        <source>Screen checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="76"/>
        <source>Method: blocks of 500 frames, threshold 0.03</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="76"/>
        <source>BirdsEye: whole flights, each checkpoint&apos;s own threshold</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="86"/>
        <source>Preset (blocks and threshold; the two fields below override it)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="89"/>
        <source>Detection threshold (empty: the preset&apos;s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="92"/>
        <source>Frames per block (0: each flight whole; empty: the preset&apos;s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="103"/>
        <source>Too sparse if detections per frame in the worst block are below</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="145"/>
        <source>{n_blocks} block(s) of {size} frames over {n_flights} flight(s); threshold {threshold}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="145"/>
        <source>all</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="145"/>
        <source>of each checkpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="194"/>
        <source>healthy</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="194"/>
        <source>collapsed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="194"/>
        <source>too sparse</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="196"/>
        <source>{checkpoint}: {state}; recall_pre {recall}, gmcf_pre {gmcf}, F1 {f1_geo}, {dpf} detections per frame, review load {load}, pixel F1 {f1_pixel} (within {radius:g} px){frontier}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="196"/>
        <source> (frontier)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SealPreregistration</name>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="70"/>
        <source>Descriptive configurations (optional: a sweep or screen JSON, recorded only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="73"/>
        <source>Note (what was chosen on which flights, what will be scored)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="76"/>
        <source>Sealed rule (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="78"/>
        <source>Seal (SHA-256)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="88"/>
        <source>CHECKPOINTS: {path} is not a file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="119"/>
        <source>OUTPUT: cannot write {out} ({exc})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="121"/>
        <source>Sealed at {sealed_at}: {seal}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="123"/>
        <source>Record this seal somewhere you cannot edit later (an e-mail, a lab notebook, a commit): the seal proves the rule unchanged only against a copy kept elsewhere.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="45"/>
        <source>Seal a preregistered selection rule</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="57"/>
        <source>ONNX checkpoints (without ARMS or ARM_LINES: one arm each)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="60"/>
        <source>Arms file (from Select arms: each arm with its own operating point)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="63"/>
        <source>Or arms typed one per line: name: checkpoint file, threshold, eps_m, min_samples, eps_pred_m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="66"/>
        <source>Detection threshold of the arms (without ARMS or ARM_LINES)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="85"/>
        <source>ARMS, ARM_LINES: give the arms file or typed arms, not both.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="91"/>
        <source>CHECKPOINTS: two files share a file name; arms name their checkpoint by file name, so rename one.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="97"/>
        <source>CHECKPOINTS: give at least one ONNX file (or an ARMS file).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="107"/>
        <source>Arm {name}: {checkpoint} (sha256 {model_digest}) at {operating_point}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SelectArms</name>
    <message>
        <location filename="../processing/algorithms/selectarms.py" line="17"/>
        <source>Select arms (max F1, max recall, lowest review burden)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/selectarms.py" line="23"/>
        <source>Sweep (the JSON output of Sweep operating points)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/selectarms.py" line="25"/>
        <source>Arms (JSON, read by Seal a preregistered selection rule)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/selectarms.py" line="38"/>
        <source>{name}: {checkpoint} at threshold {threshold:g}, eps {eps_m:g} m, min_samples {min_samples}, eps_pred {eps_pred_m:g} m → recall_pre {recall:.3f}, gmcf_pre {gmcf:.3f}, F1 {f1:.3f}, {dpf} detections per frame (row {row})</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SensorBoundAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="36"/>
        <source>Grid stride [px] (1 = every pixel)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="39"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="41"/>
        <source>Report with plots (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="44"/>
        <source>λ_max field, one band per altitude (GeoTIFF in pixel coordinates)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="99"/>
        <source>{name}: the stride {stride} px does not divide the frame size, so the raster stops at the last multiple of the stride; the JSON suprema still include the frame edges.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="108"/>
        <source>{name}: cannot create the GeoTIFF {path}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="23"/>
        <source>Sensor bound (pose-noise budget)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SimulateCampaign</name>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="98"/>
        <source>Pose noise Σ0: x, y, z (m), roll, pitch, yaw (deg)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="101"/>
        <source>Noise off (ideal poses, altimeter and geotags)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="108"/>
        <source>Terrain</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="121"/>
        <source>Geoid undulation N for altMSL (m; empty: EGM96 at the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="125"/>
        <source>Output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="129"/>
        <source>Terrain model (truth/dem.tif, ellipsoidal heights; none for flat terrain)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="134"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="105"/>
        <source>Platform</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="115"/>
        <source>Side overlap of neighbouring lines (fraction; empty: {ins:g} for the payload, {dji:g} for a DJI drone)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="119"/>
        <source>DJI drone undistorts its JPEGs (DewarpFlag 1)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="133"/>
        <source>Frames folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="169"/>
        <source>Simulating seed {seed}: {n_targets} targets in a {field_width_m:g} × {field_length_m:g} m field, flown at {altitude_m:g} m, {speed_ms:g} m/s, {fps:g} frames/s.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="176"/>
        <source>TERRAIN is flat: SLOPE_DEG and RELIEF_M are ignored (choose plane or hills).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="179"/>
        <source>TERRAIN is a plane: RELIEF_M is ignored (choose hills).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="185"/>
        <source>A DJI drone: photos on the lines with {forward_overlap:.0%} forward and {effective_side_overlap:.0%} side overlap; the pose in each JPEG&apos;s metadata carries heading, tilt and height errors (truth/dji_metadata_errors.csv).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="195"/>
        <source>Wrote {n_frames} frames, {log}{n_geotags} geotags to {folder}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="75"/>
        <source>Simulate a campaign</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="103"/>
        <source>Render frames and the orthomosaic (off: poses and geotags only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="131"/>
        <source>Orthomosaic of the field (orthomosaic.tif; none without rendering)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SweepOperatingPoints</name>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="99"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="106"/>
        <source>De-duplication grid cell (cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="113"/>
        <source>Credible: mean geotags per hit cluster at most</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="116"/>
        <source>Credible: mean median cluster extent at most (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="119"/>
        <source>Configurations (CSV)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="124"/>
        <source>Frontier plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="149"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="241"/>
        <source>No configuration passed the credibility filter.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="75"/>
        <source>Sweep operating points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="93"/>
        <source>ONNX checkpoints (run over FRAMES, peaks extracted at every threshold)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="96"/>
        <source>Or detection layers (checkpoints × flights × thresholds, from Detect)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="101"/>
        <source>Frame layers (with CHECKPOINTS: one per flight; with DETECTIONS: one per detection layer, same order)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="109"/>
        <source>Edge buffer (px) of the in-view test and of CHECKPOINTS&apos; detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="121"/>
        <source>Configurations and Pareto front (JSON, read by Select arms)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="137"/>
        <source>CHECKPOINTS, DETECTIONS: give ONNX checkpoints (the sweep runs them over the frames) or detection layers made by Detect, not both and not neither.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="141"/>
        <source>FRAMES: give at least one frame layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="143"/>
        <source>FRAMES: give one frame layer per detection layer, in the same order (got {detections} detection layer(s) and {frames} frame layer(s)).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="172"/>
        <source>{name}: {n_frames} frames, {value} geotags in view</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="180"/>
        <source>{layer}: {n} detection(s) without a position or score left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="185"/>
        <source>Threshold axis: the thresholds the layers were detected at, {values} (THRESHOLDS is used with CHECKPOINTS only).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="196"/>
        <source>Sweeping {n_checkpoints} checkpoint(s) × {size} configurations ({items}: threshold × eps × min_samples × eps_pred)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="234"/>
        <source>Pareto: {checkpoint}, threshold {threshold}, eps {eps_m} m, min_samples {min_samples}, eps_pred {eps_pred_m} m → recall_pre {recall_pre:.3f}, gmcf_pre {gmcf_pre:.3f}, F1 {f1_geo:.3f}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="276"/>
        <source>{checkpoint} on {flight}: {n} frame(s) skipped, e.g. {frame_id}: {reason}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>TerrainSlopeAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="40"/>
        <source>Altitude above the ground [m]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="44"/>
        <source>Steepest slope studied [degrees]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="47"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="49"/>
        <source>Contour plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="57"/>
        <source>{name}: the altitude must be greater than 0 m, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="62"/>
        <source>{name}: the steepest slope must lie between 0° and 90° (exclusive), got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="78"/>
        <source>{where}: {d:.2f} m from the nadir point at {alt:g} m (ρ = {rho:.3f}) — labels stay within {tol:g} px up to a {limit:.1f}° uphill slope.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="102"/>
        <source>Farthest left/right edge midpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="103"/>
        <source>Farthest top/bottom edge midpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="104"/>
        <source>Farthest frame corner</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="30"/>
        <source>Sensor bound: terrain-slope study</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>TrainDetector</name>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="47"/>
        <source>Train detector (heatmap model from training labels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="70"/>
        <source>Write-labels output folders (with tiles; pick a folder or any file in it, e.g. its summary.json)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="73"/>
        <source>Frame layers the labels were written from, for each frame&apos;s ground sample distance (one per labels folder, in the same order, or one for all)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="77"/>
        <source>Ground sample distance of every frame (cm/px), instead of frame layers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="80"/>
        <source>Network: small (from scratch, offline) or an ImageNet-pretrained encoder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="83"/>
        <source>ImageNet weights file (.pth) of a pretrained encoder (empty: torchvision&apos;s cache; nothing is downloaded)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="91"/>
        <source>Training time budget (minutes)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="93"/>
        <source>Model resolution (cm/px): tiles are resampled to it</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="96"/>
        <source>Share of the frames held out for validation (0–0.5)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="99"/>
        <source>Random seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="102"/>
        <source>Default threshold written into the model (empty: best F1 on the held-out tiles)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="105"/>
        <source>CPU threads for training (0: all cores)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="107"/>
        <source>Python with PyTorch to train in (empty: the one Install dependencies set up)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="114"/>
        <source>Trained model (ONNX)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="116"/>
        <source>Model card (Markdown)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="117"/>
        <source>Loss curves (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="118"/>
        <source>Weights to fine-tune from (.pt)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="179"/>
        <source>Train detector needs PyTorch, which it runs in a separate Python process; no Python with torch, onnx and OpenCV was found ({tried}). In QGIS, choose {menu} and install the group '{group}' ({build} build); or install it yourself: {command}; or name a Python that has them (parameter {parameter}, or the environment variable {variable}) — for a virtual environment: &lt;venv&gt;/bin/python -m pip install &quot;torch=={torch}&quot; &quot;torchvision=={torchvision}&quot; onnx opencv-python-headless matplotlib</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="179"/>
        <source>none set up</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="190"/>
        <source>Training in {python} ({origin}): torch {torch}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="226"/>
        <source>Cancelled by the user; no model was written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="235"/>
        <source>The last checkpoint is kept: {path}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="240"/>
        <source>Wrote {model} (default threshold {threshold:g}), its model card and loss plot; training {train:.1f} s on {device}, {tiles_per_s:.1f} tiles/s; {overhead:.1f} s outside training (process start, loading tiles, validation, export; the first line came after {first:.1f} s).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="87"/>
        <source>Fine-tune from an earlier model: its weights (.pt), or a BirdsEye ONNX model of the small network such as the bundled one (empty: start afresh)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>WriteLabels</name>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="82"/>
        <source>Geotags (surveyed targets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="87"/>
        <source>Soft-label σ (px); empty: the sensor-bound dock's value, else 10</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="90"/>
        <source>…or σ from a sensorbound result (JSON): r / 3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="93"/>
        <source>Edge buffer (px): geotags this close to the border are &apos;edge&apos;, not labels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="97"/>
        <source>Write one soft-label raster per frame</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="99"/>
        <source>Write a tiled training set (image and label tiles)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="101"/>
        <source>Tile size (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="104"/>
        <source>Negative tiles kept per positive tile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="107"/>
        <source>Random seed for the negative-tile sample</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="110"/>
        <source>Write COCO-keypoints JSON</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="113"/>
        <source>Label folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="114"/>
        <source>Frames with label counts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="117"/>
        <source>Geotags with frames seen</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="146"/>
        <source>GEOTAGS and FRAMES are both required.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="130"/>
        <source>SIGMA_PX is given: SENSOR_BOUND_JSON is ignored</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="136"/>
        <source>σ = {value:g} px from the project (sensor-bound calculator)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="172"/>
        <source>{n_records} frames ({n_groups} camera(s)), {n_geotags} geotags, σ = {sigma:g} px, edge buffer {edge_buffer_px:g} px</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="189"/>
        <source>{n_steep} frame(s) lie on terrain steeper than the level plane's 10° envelope (flag steep_terrain; first: {items}): their labels drift off target — give the DEM (parameter DEM)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="195"/>
        <source>{n_no_ground} frame(s) have no ground height (no usable altimeter reading, flag no_ground_height) and get no labels; first: {items}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="64"/>
        <source>Write training labels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="183"/>
        <source>{n} frame(s) could not be refined and keep their metadata pose (flag not_refined; first: {items}): their labels are only as good as the drone&apos;s metadata. Leave them out with a filter such as &quot;flags&quot; NOT LIKE &apos;%not_refined%&apos;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="84"/>
        <source>Frames (from Import flight log, Import drone images or Import camera solution)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="159"/>
        <source>From the review: {targets} target(s) nobody surveyed are labelled (provenance review); {hard} hard negative(s) put their tiles first in the negative sample.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
