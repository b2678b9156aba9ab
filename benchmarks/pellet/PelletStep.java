// The warm Pellet peer of topostore's benchmark: one OWL API ontology and one Pellet reasoner kept
// alive in one JVM, driven one robot step at a time, as aRMOR drives them.
//
// aRMOR (through aMOR) creates a buffering reasoner, applies REPLACE as RemoveAxiom + AddAxiom, and
// REASON is reasoner.flush(); queries ask the reasoner.  This program does the same calls and times
// them with System.nanoTime(), so JVM start-up, file parsing and the pipe are not in a step.
//
//   java -cp '<owlready2>/pellet/*:<classes>' PelletStep MAP.owl NAMESPACE
//
// stdin, one line per step (names are local names in NAMESPACE, times are xsd:long):
//   STEP <new location> <old location> <new now> <old now> <old visitedAt of the new location | ->
// stdout, one JSON object per line: first {"ready":...} after loading and the first REASON, then one
// {"step":...} per STEP with the step's time and both answers (local names, sorted).  EOF ends it.
// Built against the jars Owlready2 0.49 bundles: Pellet 2.3.1 and OWL API 3.4.3.

import com.clarkparsia.pellet.owlapiv3.PelletReasoner;
import com.clarkparsia.pellet.owlapiv3.PelletReasonerFactory;
import org.semanticweb.owlapi.apibinding.OWLManager;
import org.semanticweb.owlapi.model.*;
import org.semanticweb.owlapi.vocab.OWL2Datatype;

import java.io.BufferedReader;
import java.io.File;
import java.io.InputStreamReader;
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

    public static void main(String[] args) throws Exception {
        if (args.length != 2) {
            System.err.println("usage: PelletStep MAP.owl NAMESPACE");
            System.exit(2);
        }
        long t0 = System.nanoTime();
        PelletStep peer = new PelletStep(new File(args[0]), args[1]);
        long t1 = System.nanoTime();
        peer.reasoner = PelletReasonerFactory.getInstance().createReasoner(peer.ontology);  // buffering, as aMOR
        peer.reasoner.flush();  // the first REASON; Pellet checks consistency lazily, in the first query
        boolean consistent = peer.reasoner.isConsistent();
        String answers = peer.answers();
        long t2 = System.nanoTime();
        System.out.println("{\"ready\":true,\"load_ms\":" + ms(t1 - t0) + ",\"first_ms\":" + ms(t2 - t1)
                + ",\"consistent\":" + consistent + ",\"axioms\":" + peer.ontology.getAxiomCount()
                + ",\"java\":\"" + System.getProperty("java.runtime.version") + "\"," + answers + "}");
        System.out.flush();
        BufferedReader in = new BufferedReader(new InputStreamReader(System.in));
        int k = 0;
        for (String line; (line = in.readLine()) != null; ) {
            String[] f = line.trim().split(" ");
            if (f.length != 6 || !f[0].equals("STEP")) {
                System.err.println("bad command (want STEP new old now old_now old_visit): " + line);
                System.exit(2);
            }
            System.out.println(peer.step(++k, f));
            System.out.flush();
        }
        peer.reasoner.dispose();
    }
}
