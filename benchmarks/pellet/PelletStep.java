// The warm Pellet peer of topostore's benchmark: one OWL API ontology and one Pellet reasoner kept
// alive in one JVM, driven one robot step at a time, as aRMOR drives them.
//
// aRMOR (through aMOR) creates a buffering reasoner, applies REPLACE as RemoveAxiom + AddAxiom, and
// REASON is reasoner.flush(); queries ask the reasoner.  This program does the same calls and times
// them with System.nanoTime(), so JVM start-up, file parsing and the pipe are not in a step.
//
// aRMOR runs for as long as the robot does, so its JIT has long compiled Pellet's hot paths.  A
// fresh JVM has not: its first hundred steps on the example map run 2-5x slower than later ones.
// With --warmup, the JVM first loads a scratch copy of the map into a manager and reasoner of its
// own, walks it (the STEP lines of the file) until the steps or --warm-seconds run out, and throws
// it away; only then is the measured ontology loaded, so the timed steps start from the map's own
// state, in a warm JVM.
//
//   java -cp '<owlready2>/pellet/*:<classes>' PelletStep MAP.owl NAMESPACE [--warmup MOVES --warm-seconds S]
//
// stdin, one line per step (names are local names in NAMESPACE, times are xsd:long):
//   STEP <new location> <old location> <new now> <old now> <old visitedAt of the new location | ->
// stdout, one JSON object per line: first {"ready":...} after the warm-up, loading and the first
// REASON, then one {"step":...} per STEP with the step's time and both answers (local names,
// sorted).  EOF ends it.
// Built against the jars Owlready2 0.49 bundles: Pellet 2.3.1 and OWL API 3.4.3.

import com.clarkparsia.pellet.owlapiv3.PelletReasoner;
import com.clarkparsia.pellet.owlapiv3.PelletReasonerFactory;
import org.semanticweb.owlapi.apibinding.OWLManager;
import org.semanticweb.owlapi.model.*;
import org.semanticweb.owlapi.vocab.OWL2Datatype;

import java.io.BufferedReader;
import java.io.File;
import java.io.InputStreamReader;
import java.nio.file.Files;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.TreeSet;

public class PelletStep {
    private final String ns;
    private final OWLOntologyManager manager = OWLManager.createOWLOntologyManager();
    private final OWLDataFactory factory = manager.getOWLDataFactory();
    private final OWLOntology ontology;
    private PelletReasoner reasoner;

    private PelletStep(File file, String ns) throws OWLOntologyCreationException {
        this.ns = ns;
        this.ontology = manager.loadOntologyFromOntologyDocument(file);
    }

    private OWLNamedIndividual individual(String name) {
        return factory.getOWLNamedIndividual(IRI.create(ns + name));
    }

    private OWLLiteral longValue(String value) {
        return factory.getOWLLiteral(value, factory.getOWLDatatype(OWL2Datatype.XSD_LONG.getIRI()));
    }

    private OWLObjectProperty objectProperty(String name) {
        return factory.getOWLObjectProperty(IRI.create(ns + name));
    }

    private OWLDataProperty dataProperty(String name) {
        return factory.getOWLDataProperty(IRI.create(ns + name));
    }

    /** REPLACE OBJECTPROP IND: aMOR removes the old assertion and adds the new one. */
    private void replaceObject(String property, String subject, String newValue, String oldValue) {
        OWLObjectProperty p = objectProperty(property);
        manager.applyChange(new RemoveAxiom(ontology,
                factory.getOWLObjectPropertyAssertionAxiom(p, individual(subject), individual(oldValue))));
        manager.applyChange(new AddAxiom(ontology,
                factory.getOWLObjectPropertyAssertionAxiom(p, individual(subject), individual(newValue))));
    }

    /** REPLACE DATAPROP IND with type Long; no old value ("-") makes it an ADD. */
    private void replaceLong(String property, String subject, String newValue, String oldValue) {
        OWLDataProperty p = dataProperty(property);
        if (!oldValue.equals("-"))
            manager.applyChange(new RemoveAxiom(ontology,
                    factory.getOWLDataPropertyAssertionAxiom(p, individual(subject), longValue(oldValue))));
        manager.applyChange(new AddAxiom(ontology,
                factory.getOWLDataPropertyAssertionAxiom(p, individual(subject), longValue(newValue))));
    }

    /** QUERY OBJECTPROP IND canReach Robot1 and QUERY IND CLASS URGENT, as sorted local names. */
    private String answers() {
        Set<OWLNamedIndividual> reach = reasoner.getObjectPropertyValues(individual("Robot1"),
                objectProperty("canReach")).getFlattened();
        Set<OWLNamedIndividual> urgent = reasoner.getInstances(
                factory.getOWLClass(IRI.create(ns + "URGENT")), false).getFlattened();
        return "\"canReach\":" + names(reach) + ",\"urgent\":" + names(urgent);
    }

    private String names(Set<OWLNamedIndividual> individuals) {
        TreeSet<String> sorted = new TreeSet<>();
        for (OWLNamedIndividual i : individuals) {
            String iri = i.getIRI().toString();
            sorted.add(iri.startsWith(ns) ? iri.substring(ns.length()) : iri);
        }
        List<String> quoted = new ArrayList<>();
        for (String s : sorted) quoted.add("\"" + s.replace("\\", "\\\\").replace("\"", "\\\"") + "\"");
        return "[" + String.join(",", quoted) + "]";
    }

    /** One robot step: the three REPLACEs, REASON (flush) and the two queries. */
    private String step(int k, String[] f) {
        long start = System.nanoTime();
        replaceObject("isIn", "Robot1", f[1], f[2]);
        replaceLong("now", "Robot1", f[3], f[4]);
        replaceLong("visitedAt", f[1], f[3], f[5]);
        long flushStart = System.nanoTime();
        reasoner.flush();
        long flushEnd = System.nanoTime();
        String answers = answers();
        long end = System.nanoTime();
        return "{\"step\":" + k + ",\"ms\":" + ms(end - start) + ",\"flush_ms\":" + ms(flushEnd - flushStart)
                + ",\"queries_ms\":" + ms(end - flushEnd) + "," + answers + "}";
    }

    private static String ms(long nanos) {
        return String.valueOf(nanos / 1e6);
    }

    /** The first REASON (flush; consistency and the first answers are computed lazily by Pellet). */
    private String firstReason() {
        reasoner = PelletReasonerFactory.getInstance().createReasoner(ontology);  // buffering, as aMOR
        reasoner.flush();
        return ",\"consistent\":" + reasoner.isConsistent() + "," + answers();
    }

    /**
     * Warm the JIT on a scratch copy of the map: its own manager, ontology and reasoner, walked
     * through the moves until they or the seconds run out, then disposed.  Returns the JSON fields
     * {warm_steps, warm_ms, warm_step_ms}; the step times show the JIT's curve.
     */
    private static String warmUp(File map, String ns, File moves, double seconds) throws Exception {
        long start = System.nanoTime();
        PelletStep scratch = new PelletStep(map, ns);
        scratch.firstReason();
        List<String> times = new ArrayList<>();
        for (String line : Files.readAllLines(moves.toPath())) {
            if (line.isBlank()) continue;
            if (!times.isEmpty() && (System.nanoTime() - start) / 1e9 > seconds) break;  // one step at least
            long s0 = System.nanoTime();
            scratch.step(times.size() + 1, parse(line));
            times.add(ms(System.nanoTime() - s0));
        }
        scratch.reasoner.dispose();
        scratch.manager.removeOntology(scratch.ontology);
        System.gc();
        return "\"warm_steps\":" + times.size() + ",\"warm_ms\":" + ms(System.nanoTime() - start)
                + ",\"warm_step_ms\":[" + String.join(",", times) + "],";
    }

    private static String[] parse(String line) {
        String[] f = line.trim().split(" ");
        if (f.length != 6 || !f[0].equals("STEP")) {
            System.err.println("bad command (want STEP new old now old_now old_visit): " + line);
            System.exit(2);
        }
        return f;
    }

    public static void main(String[] args) throws Exception {
        if (args.length != 2 && !(args.length == 6 && args[2].equals("--warmup") && args[4].equals("--warm-seconds"))) {
            System.err.println("usage: PelletStep MAP.owl NAMESPACE [--warmup MOVES --warm-seconds S]");
            System.exit(2);
        }
        File map = new File(args[0]);
        String warm = args.length == 6 ? warmUp(map, args[1], new File(args[3]), Double.parseDouble(args[5])) : "";
        long t0 = System.nanoTime();
        PelletStep peer = new PelletStep(map, args[1]);
        long t1 = System.nanoTime();
        String first = peer.firstReason();
        long t2 = System.nanoTime();
        System.out.println("{\"ready\":true," + warm + "\"load_ms\":" + ms(t1 - t0) + ",\"first_ms\":" + ms(t2 - t1)
                + ",\"axioms\":" + peer.ontology.getAxiomCount()
                + ",\"java\":\"" + System.getProperty("java.runtime.version") + "\"" + first + "}");
        System.out.flush();
        BufferedReader in = new BufferedReader(new InputStreamReader(System.in));
        int k = 0;
        for (String line; (line = in.readLine()) != null; ) {
            System.out.println(peer.step(++k, parse(line)));
            System.out.flush();
        }
        peer.reasoner.dispose();
    }
}
